"""What we chose where the thesis is silent, and the number each choice changes (the report's
"What we chose" table; docs/model.md §3.3, §5, docs/env1.md).

Each entry: what we chose, the alternative, and either the study numbers that show the
difference (keys of a study's `numbers`, ours then the alternative) or a measured number that no
study recomputes (with where it was measured). `rows(numbers)` fills the table from a run.
"""

from __future__ import annotations

CHOICES = [
    {
        "choice": "Frame of DELV's current landmark list",
        "ours": "home frame of the compass reading / each heading hypothesis (SPEC §3.3, thesis Fig 3.4), as ACV",
        "alternative": "agent frame (the earlier order; `delv-compass-agent`)",
        "measure": "env1 catchment of DELV with a compass, k = 0/1/2 hidden landmarks (%)",
        "keys": ("gap:env1:delv-compass:catchment", "gap:env1:delv-compass-agent:catchment"),
    },
    {
        "choice": "First move of a rollout",
        "ours": "thesis Algorithm 2: DELV moves d along the release heading, then matches",
        "alternative": "the direction computed at the release point (`--first-move homing`, the earlier default)",
        "measure": "catchment of DELV without a compass, env1 (%)",
        "keys": ("catchment:env1:delv", "catchment:env1:delv:homing"),
    },
    {
        "choice": "First move of a rollout (env3)",
        "ours": "thesis Algorithm 2",
        "alternative": "the direction computed at the release point",
        "measure": "catchment of DELV without a compass, env3 (%)",
        "keys": ("catchment:env3:delv", "catchment:env3:delv:homing"),
    },
    {
        "choice": "Grid points near the walls",
        "ours": "under Algorithm 2 the catchment counts grid points at least d from every wall (the same for every "
        "method); the vector map keeps them",
        "alternative": "count a blind first move out of the arena as a failure",
        "measure": "points counted on the default 40 x 40 grid with d = 50",
        "static": "1296 of 1600 cells (minus those near landmarks) instead of all 1600; counting the exits as "
        "failures charged DELV with 105 arena exits from cells 12.5 cm from a wall (the fidelity review)",
    },
    {
        "choice": "Landmarks as obstacles",
        "ours": "no (collisions = ignore): the thesis's 100 % ALV catchment (Table 5.3) needs it",
        "alternative": "a move ending inside a landmark fails (physical rules)",
        "measure": "catchment of ALV with a compass, env1 (%)",
        "keys": ("occlusion:env1:alv:catchment", "occlusion:env1:alv:catchment:physical"),
    },
    {
        "choice": "The env1 layout",
        "ours": "screened from about 460 random asymmetric layouts, partly for the hull claim (docs/env1.md)",
        "alternative": "the first env1 (near a 90° ring)",
        "measure": "DELV without compass, e > 45 % inside / outside the landmark hull (seeds 0-9)",
        "static": "3.11 / 3.13 (ours) against 7.18 / 1.06 (the first layout): the hull claim holds partly because "
        "the layout was chosen for it",
    },
    {
        "choice": "Landmarks off the home move's line",
        "ours": "every built-in layout keeps its landmarks at least 20° off the line of the home unit move",
        "alternative": "a landmark on that line (no parallax: its distance becomes r_max)",
        "measure": "catchment of DELV on env1 with one landmark moved onto the line (%)",
        "static": "100 -> 17 (measured in the fidelity review, earlier rules)",
    },
    {
        "choice": "Sensing noise",
        "ours": "none by default (the thesis gives no noise model)",
        "alternative": "the best combination of bearing and odometry noise, home radius and rules over the world "
        "ensembles (the `ensemble_settings` study)",
        "measure": "mean CRPS of the thesis's numbers of Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3 over the members (points)",
        "keys": ("ensemble_settings:score:default", "ensemble_settings:score:best"),
    },
]


def _fmt(v) -> str:
    if isinstance(v, (list, tuple)):
        return "/".join(_fmt(x) for x in v)
    return f"{v:.1f}" if isinstance(v, (int, float)) else str(v)


def rows(numbers: dict) -> list[dict]:
    """The table's rows: each choice with its number under our choice and under the alternative,
    read from `numbers` (key -> value, every study of the run) where a study made it."""
    out = []
    for c in CHOICES:
        if "keys" in c:
            ours, alt = (numbers.get(k) for k in c["keys"])
            value = "not run" if ours is None else f"{_fmt(ours)} (alternative {_fmt(alt) if alt is not None else '–'})"
        else:
            value = c["static"]
        out.append(
            {
                "choice": c["choice"],
                "ours": c["ours"],
                "alternative": c["alternative"],
                "what it changes": f"{c['measure']}: {value}",
            }
        )
    return out
