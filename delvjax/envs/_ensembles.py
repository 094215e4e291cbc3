"""World ensembles: every layout the thesis's words allow for each of its worlds (docs/model.md §6.1).

The thesis describes its environments in words only (thesis §4.2, line 518-530; §5.3.1, Tables
5.2/5.4; the robot arena of §4.4.1), so a claim about them is judged over a family of layouts consistent
with the words (SPEC §8). A family draws its members with `jax.random`: member `i` of seed `s` comes from the key
`fold_in(PRNGKey(s), i)` alone, so a member does not depend on how many are asked for. Each member
is the first of `CANDIDATES` candidate layouts that satisfies every rule of its family; all
members' candidates are drawn and checked as one array program (vmap over members and candidates).
`violations` is the plain check of a layout against its family's rules (used after drawing, by the
tests, and to say which built-in worlds are members).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from ..core.errors import InputError
from ..core.scene import DEFAULT_ARENA, DEFAULT_HOME

CANDIDATES = 256  # candidate layouts drawn per member and round (a round accepts > 99.99 % of members)
ROUNDS = 16  # rounds of candidates before a member is given up (never seen: the test draws 4096 members)
MAX_MEMBERS = 100_000  # members one call may ask for
MEMBER_CHUNK = 4096  # members drawn by one program call (memory: 256 candidates each)
EPS = 1e-3  # the drawn layouts keep this margin (cm, degrees) from every rule's bound: rounding keeps them members


@dataclass(frozen=True)
class Family:
    """A family of layouts (SPEC §8; docs/model.md §6.1): `n` landmarks whose centres lie
    `distance` cm from home and radii `radius` cm, surfaces at least `surface_gap` cm apart and every
    centre at least `off_line_deg` degrees off the line of the home unit move (world angle 0/180,
    alpha_r = 0, §3.1: a landmark on it gives no parallax). `kind` says how bearings are drawn:
    "around" (independent, largest gap seen from home < 180°, no rotation by 90/180/270° about home
    within `asymmetry_cm` of the layout), "square" (90° apart, one common rotation), "side" (within a
    `sector_deg` sector, so home lies outside the hull) or "ring" (equally spaced, one common
    distance and radius). `home` and `arena` are the world's (the default's; the robot family's
    180 cm arena, `in_arena`)."""

    name: str
    kind: str
    n: int
    description: str
    source: str
    distance: tuple[float, float] = (150.0, 350.0)
    radius: tuple[float, float] = (15.0, 50.0)
    surface_gap: float = 20.0
    home_gap: float = 10.0
    off_line_deg: float = 20.0
    asymmetry_cm: float = 50.0
    sector_deg: float = 150.0
    home: tuple[float, float] = DEFAULT_HOME
    arena: tuple[float, float, float, float] = DEFAULT_ARENA

    @property
    def unit(self) -> float:
        """The arena's side over the default arena's (1 for the thesis's simulated worlds, 0.18 for the robot's)."""
        return (self.arena[2] - self.arena[0]) / (DEFAULT_ARENA[2] - DEFAULT_ARENA[0])

    def scaled(self, factor: float) -> "Family":
        """The family with its distance and radius ranges narrowed (factor < 1) or widened (> 1) about
        their centres (SPEC §8: "narrowed or widened by a third"); distances stay >= 60 cm and radii >= 5 cm
        (times `unit`), which only factors above 1.57 reach."""
        if not (isinstance(factor, (int, float)) and 0 < factor <= 2):
            raise InputError("factor", factor, "must be a number in (0, 2]")

        def scale(lo: float, hi: float, floor: float) -> tuple[float, float]:
            mid, half = (lo + hi) / 2, (hi - lo) / 2 * factor
            return (max(floor * self.unit, mid - half), mid + half)

        return dataclasses.replace(
            self, distance=scale(*self.distance, 60.0), radius=scale(*self.radius, 5.0), name=f"{self.name}x{factor:g}"
        )

    def in_arena(self, scale: float) -> "Family":
        """This family in an arena `scale` times the default's side, home at its centre: every length rule
        (distances, radii, gaps, asymmetry) times `scale`, angles as they are (SPEC §8's robot family)."""
        times = lambda pair: (round(pair[0] * scale, 6), round(pair[1] * scale, 6))  # noqa: E731
        side = (DEFAULT_ARENA[2] - DEFAULT_ARENA[0]) * scale
        return dataclasses.replace(
            self,
            distance=times(self.distance),
            radius=times(self.radius),
            surface_gap=round(self.surface_gap * scale, 6),
            home_gap=round(self.home_gap * scale, 6),
            asymmetry_cm=round(self.asymmetry_cm * scale, 6),
            home=(side / 2, side / 2),
            arena=(0.0, 0.0, side, side),
        )


_AROUND = "thesis §4.2 (line 518): 'Four landmarks are asymmetrically surrounding the home location'"
_SQUARE = (
    "thesis §4.2 (line 518-530): 'the bearing angle of each landmark, as seen at the goal location, differs by "
    "90° from that of its neighboring landmark'"
)
_SIDE = "thesis §4.2 (line 530): 'all four landmarks in the third environment are cornered to one side of the home'"
_RING = "thesis §5.3.1 (line 881): 'equally distributed landmarks configuration with different landmark numbers'"
_SIZES = "thesis §4.2 (line 518): 'four cylindrical landmarks but with different sizes and angular positions'"
_ROBOT = (
    "thesis §4.4.1 (line 642): 'Four landmarks are red-colored cylindrical objects, and the experimental environment "
    "has a total area of 1.8 meters by 1.8 meters'; §4.1 (line 491): 'The environment for simulation experiments were "
    "set similar to that of a real-world robotic experiment'"
)
ROBOT_SCALE = 0.18  # the robot's arena side (180 cm, thesis §4.4.1) over the simulated worlds' (1000 cm, SPEC §1)

# The ring of L = 5 cannot keep every landmark 20° off the home unit move's line (its bearings mod 180° are
# 36° apart, so the best rotation keeps 18°): that family keeps 15° (docs/model.md §6.1).
FAMILIES: dict[str, Family] = {
    "env1": Family("env1", "around", 4, "four landmarks around home, asymmetric", f"{_AROUND}; {_SIZES}"),
    "env2": Family("env2", "square", 4, "four landmarks at bearings 90° apart", f"{_SQUARE}; {_SIZES}"),
    "env3": Family("env3", "side", 4, "four landmarks on one side of home", f"{_SIDE}; {_SIZES}"),
    **{
        f"ring{n}": Family(
            f"ring{n}",
            "ring",
            n,
            f"{n} landmarks equally spaced, one distance and radius",
            _RING,
            off_line_deg=15.0 if n == 5 else 20.0,
        )
        for n in range(3, 7)
    },
}
# The robot arena (SPEC §8, thesis §4.4.1): env1's rules with every length times 0.18, home at the arena's centre
# (docs/model.md §6.1; the built-in robot world of docs/images.md §8 misses its distance range, tested).
FAMILIES["robot"] = dataclasses.replace(
    FAMILIES["env1"].in_arena(ROBOT_SCALE),
    name="robot",
    description="four red cylinders around home in the 1.8 m arena, asymmetric",
    source=f"{_ROBOT}; {_AROUND}",
)


def family(name: str) -> Family:
    """The family called `name` (FAMILIES); `InputError` naming `ensemble` otherwise."""
    if name not in FAMILIES:
        raise InputError("ensemble", name, f"unknown world family (choose from {', '.join(FAMILIES)})")
    return FAMILIES[name]


# --- drawing (one array program) ------------------------------------------------------------------


def _uniform(key, shape, bounds):
    return jax.random.uniform(key, shape, minval=bounds[0], maxval=bounds[1], dtype=jnp.float32)


def _bearings(key, fam: Family, k: int):
    """(k, n) bearings from home (radians) of `k` candidates, by the family's kind."""
    n = fam.n
    if fam.kind == "around":
        return jax.random.uniform(key, (k, n), maxval=2 * math.pi, dtype=jnp.float32)
    if fam.kind == "side":
        k1, k2 = jax.random.split(key)
        half = math.radians(fam.sector_deg) / 2
        centre = jax.random.uniform(k1, (k, 1), maxval=2 * math.pi, dtype=jnp.float32)
        return centre + jax.random.uniform(k2, (k, n), minval=-half, maxval=half, dtype=jnp.float32)
    spacing = 2 * math.pi / n  # "square" (n = 4) and "ring": one common rotation
    return jax.random.uniform(key, (k, 1), maxval=spacing, dtype=jnp.float32) + spacing * jnp.arange(n)


def _ranges(fam: Family, bounds) -> tuple:
    """(distance lo, hi, radius lo, hi): `bounds` where given (traced, `_first_valid`), else the family's."""
    return (*fam.distance, *fam.radius) if bounds is None else tuple(bounds[i] for i in range(4))


def _draw(key, fam: Family, k: int, bounds=None):
    """(k, n, 3) candidate layouts [x, y, r] and their (k, n) bearings."""
    kb, kd, kr = jax.random.split(key, 3)
    d0, d1, r0, r1 = _ranges(fam, bounds)
    bearing = _bearings(kb, fam, k)
    common = fam.kind == "ring"
    dist = _uniform(kd, (k, 1 if common else fam.n), (d0, d1)) * jnp.ones((k, fam.n))
    rad = _uniform(kr, (k, 1 if common else fam.n), (r0, r1)) * jnp.ones((k, fam.n))
    hx, hy = fam.home
    xy = jnp.stack([hx + dist * jnp.cos(bearing), hy + dist * jnp.sin(bearing)], axis=-1)
    return jnp.concatenate([jnp.round(xy * 100) / 100, jnp.round(rad[..., None] * 100) / 100], axis=-1)


def _rules(xyr, fam: Family, xp, bounds=None):
    """Per layout (..., n, 3): a dict of rule -> bool (..., ) that the layout keeps, written once for
    both jnp (drawing) and numpy (`violations`); `eps` is the margin kept from every bound; `bounds` as `_draw`."""
    eps = EPS if xp is jnp else 0.0
    d0, d1, r0, r1 = _ranges(fam, bounds)
    home = xp.asarray(fam.home)
    rel = xyr[..., :2] - home
    dist = xp.sqrt(xp.sum(rel**2, axis=-1))
    r = xyr[..., 2]
    bearing = xp.arctan2(rel[..., 1], rel[..., 0])
    n = xyr.shape[-2]
    i, j = np.triu_indices(n, 1)
    centres = xp.sqrt(xp.sum((xyr[..., i, :2] - xyr[..., j, :2]) ** 2, axis=-1))
    off_line = xp.degrees(xp.arcsin(xp.clip(xp.abs(xp.sin(bearing)), 0.0, 1.0)))
    rules = {
        "distance": xp.all((dist >= d0 + eps) & (dist <= d1 - eps), axis=-1),
        "radius": xp.all((r >= r0 - 0.01) & (r <= r1 + 0.01), axis=-1),
        "surface_gap": xp.all(centres - r[..., i] - r[..., j] >= fam.surface_gap + eps, axis=-1),
        "home_gap": xp.all(dist - r >= fam.home_gap + eps, axis=-1),
        "off_line": xp.all(off_line >= fam.off_line_deg + eps, axis=-1),
    }
    gaps = angular_gaps_deg(bearing, xp)
    if fam.kind == "around":
        rules["around"] = xp.max(gaps, axis=-1) < 180.0 - eps
        rules["asymmetric"] = _asymmetry(rel, xp) > fam.asymmetry_cm + eps
    elif fam.kind == "side":  # every bearing inside one sector: the largest gap leaves the rest of the circle
        rules["one_side"] = xp.max(gaps, axis=-1) > 360.0 - fam.sector_deg + eps
    else:  # equal angular spacing (a common rotation)
        rules["equal_spacing"] = xp.all(xp.abs(gaps - 360.0 / n) < 0.1, axis=-1)
        if fam.kind == "ring":
            rules["common_distance_radius"] = (xp.ptp(dist, axis=-1) < 0.1) & (xp.ptp(r, axis=-1) < 0.02)
    return rules


def angular_gaps_deg(bearing, xp):
    """(..., n) the angular gaps (degrees) between consecutive bearings (radians) seen from home, around the circle."""
    order = xp.sort(xp.mod(bearing, 2 * math.pi), axis=-1)
    return xp.degrees(xp.diff(xp.concatenate([order, order[..., :1] + 2 * math.pi], axis=-1), axis=-1))


def _asymmetry(rel, xp):
    """(...,) the smallest over the rotations by 90, 180 and 270° about home of the bottleneck distance
    (cm) between the rotated and the original centres (`core.scene.rotation_mismatch`): the best
    one-to-one matching's largest move, over every permutation of the n landmarks."""
    n = rel.shape[-2]
    perms = np.array(list(itertools.permutations(range(n))))  # (n!, n): 24 for four landmarks
    worst = []
    for deg in (90.0, 180.0, 270.0):  # three fixed rotations
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        rot = xp.stack([c * rel[..., 0] - s * rel[..., 1], s * rel[..., 0] + c * rel[..., 1]], axis=-1)
        moved = xp.sqrt(xp.sum((rot[..., None, :, :] - rel[..., perms, :]) ** 2, axis=-1))  # (..., n!, n)
        worst.append(xp.min(xp.max(moved, axis=-1), axis=-1))
    return xp.min(xp.stack(worst, axis=-1), axis=-1)


@partial(jax.jit, static_argnames=("shape", "size"))
def _first_valid(base, first, rnd, shape: Family, bounds, size: int):
    """For members first .. first + size - 1 (key `fold_in(base, i)`, in round `rnd` > 0 folded again with
    `rnd`): each one's first valid candidate (n, 3) and whether one was found. `shape` is the family without
    its ranges (static), `bounds` its [distance lo, hi, radius lo, hi] (traced): a family narrowed or widened
    (`Family.scaled`) runs the program of its default; `size` is a bucket of member counts (`member_chunk`)."""
    keys = jax.vmap(lambda i: jax.random.fold_in(base, i))(first + jnp.arange(size))
    keys = jnp.where(rnd == 0, keys, jax.vmap(lambda k: jax.random.fold_in(k, rnd))(keys))

    def one(key):
        cands = _draw(key, shape, CANDIDATES, bounds)
        ok = jnp.all(jnp.stack(list(_rules(cands, shape, jnp, bounds).values())), axis=0)
        pick = jnp.argmax(ok)
        return cands[pick], ok[pick]

    return jax.vmap(one)(keys)


def member_chunk(members: int) -> int:
    """The members one `_first_valid` call draws: a power of two >= `members` (at least 8, at most
    MEMBER_CHUNK), so that a handful of programs serve every member count (the padding is dropped)."""
    return min(max(8, 1 << (int(members) - 1).bit_length()), MEMBER_CHUNK)


def member_layouts(name: str | Family, members: int, seed: int = 0) -> np.ndarray:
    """(members, n, 3) layouts [x, y, r] (cm) of family `name`: member i from `fold_in(PRNGKey(seed), i)`."""
    fam = name if isinstance(name, Family) else family(name)
    if isinstance(members, bool) or not isinstance(members, (int, np.integer)) or not 1 <= members <= MAX_MEMBERS:
        raise InputError("members", members, f"must be an integer in 1..{MAX_MEMBERS}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InputError("seed", seed, "must be an integer >= 0")
    shape = dataclasses.replace(fam, name="", distance=(0.0, 0.0), radius=(0.0, 0.0))  # one program per shape
    bounds = np.asarray([*fam.distance, *fam.radius], np.float32)
    base = jax.random.PRNGKey(int(seed))
    size = member_chunk(members)
    out = np.zeros((members, fam.n, 3))
    for start in range(0, members, size):  # chunks of a bounded size (memory), not a loop over members
        n = min(size, members - start)
        todo = np.ones(n, bool)
        for rnd in range(ROUNDS):  # rounds of candidates, not a loop over members
            layout, ok = (
                np.asarray(a)[:n] for a in _first_valid(base, np.int32(start), np.int32(rnd), shape, bounds, size)
            )
            take = todo & ok
            out[start : start + n][take] = layout[take]
            todo &= ~ok
            if not todo.any():
                break
        if todo.any():
            raise InputError(
                "ensemble", fam.name, f"found no layout for {int(todo.sum())} members: the rules leave none"
            )
    return out.round(2)


def violations(name: str | Family, landmarks, home=None) -> list[str]:
    """The rules of family `name` that a layout (rows x, y, r; home as given, else the family's) breaks: [] for
    a member."""
    fam = name if isinstance(name, Family) else family(name)
    xyr = np.asarray(landmarks, float).reshape(-1, 3)
    if xyr.shape[0] != fam.n:
        return [f"landmarks: {xyr.shape[0]}, the family has {fam.n}"]
    shifted = xyr.copy()
    if home is not None:  # the rules are about home
        shifted[:, :2] += np.asarray(fam.home) - np.asarray(home, float)
    return [rule for rule, ok in _rules(shifted, fam, np).items() if not bool(ok)]


def ensemble_envs(name: str, members: int, seed: int = 0, factor: float = 1.0, first: int = 0) -> list[dict]:
    """Members `first` .. `first + members - 1` as docs/model.md §7 dictionaries, named `<family>-m<i>` (seed 0)
    or `<family>-s<seed>-m<i>` (`<family>x<factor>-...` where `factor` narrows or widens the ranges,
    `Family.scaled`)."""
    fam = family(name) if factor == 1.0 else family(name).scaled(factor)
    if isinstance(first, bool) or not isinstance(first, (int, np.integer)) or not 0 <= first < MAX_MEMBERS:
        raise InputError("first", first, f"must be an integer in 0..{MAX_MEMBERS - 1}")
    layouts = member_layouts(fam, first + members, seed)[first:]
    prefix = (name if factor == 1.0 else fam.name) + ("-m" if seed == 0 else f"-s{seed}-m")
    return [
        {
            "name": f"{prefix}{i}",
            "arena": list(fam.arena),
            "home": list(fam.home),
            "landmarks": [{"x": float(x), "y": float(y), "r": float(r)} for x, y, r in lay],
        }
        for i, lay in enumerate(layouts, start=first)
    ]


# --- properties that may decide a claim ---------------------------------------------------------

PROPERTIES = {
    "centroid_cm": "distance of the landmark centroid from home (cm)",
    "largest_gap_deg": "largest angular gap between landmarks seen from home (°)",
    "nearest_cm": "distance of the nearest landmark centre from home (cm)",
    "farthest_cm": "distance of the farthest landmark centre from home (cm)",
    "radius_ratio": "largest over smallest landmark radius",
    "off_line_deg": "smallest angle of a landmark off the home unit move's line (°)",
}


def world_properties(layouts, home=DEFAULT_HOME) -> dict[str, np.ndarray]:
    """(W,) arrays of each of PROPERTIES for layouts (W, n, 3) around `home` (the default home; a robot member's
    is its family's, (90, 90))."""
    xyr = np.asarray(layouts, float)
    rel = xyr[..., :2] - np.asarray(home, float)
    dist = np.hypot(rel[..., 0], rel[..., 1])
    bearing = np.mod(np.arctan2(rel[..., 1], rel[..., 0]), 2 * math.pi)
    gaps = angular_gaps_deg(bearing, np)
    return {
        "centroid_cm": np.hypot(*rel.mean(axis=-2).T),
        "largest_gap_deg": gaps.max(axis=-1),
        "nearest_cm": dist.min(axis=-1),
        "farthest_cm": dist.max(axis=-1),
        "radius_ratio": xyr[..., 2].max(axis=-1) / xyr[..., 2].min(axis=-1),
        "off_line_deg": np.degrees(np.arcsin(np.abs(np.sin(bearing)))).min(axis=-1),
    }
