"""Property tests (hypothesis): random valid environments never give NaN where a result is valid,
random invalid ones give an `InputError` naming the field, and random CLI argument lists exit 0 or 2.

Kept cheap: every valid environment is padded to 12 landmarks and has a 12-cell grid (the arena
is drawn as nx x ny cells with nx * ny = 12), so each method compiles once.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import delvjax
from delvjax import Grid, InputError
from delvjax.envs._presets import env_from_dict, load_env
from tests import hints_unchecked
from tests.cases.strategies import FAST, JUNK

PAD = 12
GRIDS = [(1, 12), (2, 6), (3, 4), (4, 3), (6, 2), (12, 1)]  # nx * ny = 12 grid points: one shape
METHODS = ("delv", "alv", "warping")


def fits(lms, x, y, r, arena, home) -> bool:
    """docs/model.md §2.1 / §7: r > 0, inside the arena, not covering home, overlapping no other."""
    xmin, ymin, xmax, ymax = arena
    return (
        r > 0
        and math.hypot(x - home[0], y - home[1]) > r
        and xmin <= x - r
        and x + r <= xmax
        and ymin <= y - r
        and y + r <= ymax
        and all(math.hypot(x - a, y - b) >= r + c for a, b, c in lms)
    )


@st.composite
def scenes(draw):
    """(landmarks, home, arena, spacing) of a valid environment with a 12-point grid."""
    nx, ny = draw(st.sampled_from(GRIDS))
    s = draw(st.floats(100.0, 400.0))
    w, h = (s * (n - 0.5 + draw(st.floats(0.05, 0.95))) for n in (nx, ny))
    x0, y0 = draw(st.floats(-1e4, 1e4)), draw(st.floats(-1e4, 1e4))
    arena = (x0, y0, x0 + w, y0 + h)
    home = (x0 + w * draw(st.floats(0.001, 0.999)), y0 + h * draw(st.floats(0.001, 0.999)))
    big = max(min(w, h) / 2, 1.0)
    lms: list[tuple[float, float, float]] = []
    if draw(st.booleans()):  # one landmark just clear of home: the hardest views
        r, gap, a = draw(st.floats(0.5, big)), draw(st.floats(1e-3, 5.0)), draw(st.floats(0.0, 2 * math.pi))
        x, y = home[0] + (r + gap) * math.cos(a), home[1] + (r + gap) * math.sin(a)
        if fits(lms, x, y, r, arena, home):
            lms.append((x, y, r))
    for _ in range(draw(st.integers(1, 12))):
        r = draw(st.one_of(st.floats(0.01, 5.0), st.floats(5.0, 60.0), st.floats(1.0, big)))
        x, y = x0 + w * draw(st.floats(0.0, 1.0)), y0 + h * draw(st.floats(0.0, 1.0))
        if fits(lms, x, y, r, arena, home):
            lms.append((x, y, r))
    if not lms:  # a landmark in the arena corner farthest from home always fits when it is small
        r = min(w, h) / 8
        lm = (
            x0 + 1.5 * r if home[0] - x0 > w / 2 else x0 + w - 1.5 * r,
            y0 + 1.5 * r if home[1] - y0 > h / 2 else y0 + h - 1.5 * r,
            r,
        )
        assert fits([], *lm, arena, home)
        lms.append(lm)
    return lms, home, arena, s


@settings(max_examples=25, **FAST)
@given(
    scene=scenes(),
    seed=st.integers(0, 2**32 - 1),
    clearance=st.floats(0.0, 50.0),
    d=st.floats(0.5, 500.0),
    noise=st.sampled_from([{}, {"bearing_noise_deg": 3.0, "step_noise": 0.1, "turn_noise_deg": 5.0}]),
)
def test_valid_environments_give_finite_results_where_valid(scene, seed, clearance, d, noise):
    lms, home, arena, spacing = scene
    env = delvjax.make_env(lms, home=home, arena=arena, pad_to=PAD)
    assert env.n_landmarks == len(lms)
    for method in METHODS:
        try:
            vm = delvjax.vector_map(
                env, method=method, seed=seed, d=d, grid=Grid(spacing=spacing, clearance=clearance), **noise
            )
        except InputError as exc:
            # the only refusals of a valid scene: no grid point clear, a method that reads panoramas, or every
            # landmark narrower from home than the default ring's 1-degree pixel (options._limits.check_pixels)
            widest = max(2 * np.degrees(np.arcsin(min(r / np.hypot(x - home[0], y - home[1]), 1.0))) for x, y, r in lms)
            assert (
                exc.field == "spacing"
                or (exc.field == "method" and "panoramas" in str(exc))
                or (exc.field == "n_pix" and widest < 1.0)
            ), exc
            continue
        valid, direction, error = (np.asarray(a) for a in (vm.valid, vm.direction, vm.error_deg))
        assert np.isfinite(np.asarray(vm.points)).all() and np.isfinite(np.asarray(vm.heading)).all()
        assert np.isfinite(direction[valid]).all(), (method, direction, valid)
        assert not np.isnan(error).any() and (error[~valid] == 180.0).all(), (method, error)
        assert ((error >= 0.0) & (error <= 180.0)).all()


@st.composite
def broken_specs(draw):
    """(environment dictionary with one documented fault, the field its error must name)."""
    x0, y0 = draw(st.floats(-1e4, 1e4)), draw(st.floats(-1e4, 1e4))
    w, h = draw(st.floats(200.0, 3000.0)), draw(st.floats(200.0, 3000.0))
    arena, home = [x0, y0, x0 + w, y0 + h], [x0 + w / 2, y0 + h / 2]
    lms = [(x0 + 40.0, y0 + 40.0, 30.0)]
    if draw(st.booleans()):
        lms.append((x0 + w - 50.0, y0 + h - 50.0, draw(st.floats(0.01, 45.0))))
    spec = {"name": "t", "arena": arena, "home": home, "landmarks": [{"x": x, "y": y, "r": r} for x, y, r in lms]}
    n, i = len(lms), draw(st.integers(0, len(lms) - 1))
    fault = draw(
        st.sampled_from(
            [
                "number",
                "radius",
                "overlap",
                "home_covered",
                "landmark_outside",
                "home_outside",
                "arena_order",
                "arena_shape",
                "no_landmarks",
                "missing",
                "unknown",
                "lm_missing",
                "lm_unknown",
                "lm_type",
                "name",
                "type",
            ]
        )
    )
    if fault == "number":
        field = draw(
            st.sampled_from(
                [f"arena[{k}]" for k in range(4)] + ["home[0]", "home[1]"] + [f"landmarks[{i}].{k}" for k in "xyr"]
            )
        )
        key, sub = field.split("[", 1)
        target = spec["landmarks"][i] if key == "landmarks" else spec[key]
        target[sub[-1] if key == "landmarks" else int(sub[0])] = draw(JUNK)
        return spec, field
    new = {"x": arena[0] + w / 3, "y": home[1], "r": 10.0}  # a landmark that fits, to be spoilt below
    if fault == "radius":
        spec["landmarks"][i]["r"] = draw(st.floats(max_value=0.0))
        return spec, f"landmarks[{i}].r"
    if fault == "overlap":
        a, t = draw(st.floats(0.0, 2 * math.pi)), draw(st.floats(0.0, 0.99))
        reach = t * (lms[i][2] + 10.0)
        new = {"x": lms[i][0] + reach * math.cos(a), "y": lms[i][1] + reach * math.sin(a), "r": 10.0}
    elif fault == "home_covered":
        r = draw(st.floats(0.01, 100.0))
        new = {"x": home[0] + draw(st.floats(-0.99, 0.99)) * r, "y": home[1], "r": r}
    elif fault == "landmark_outside":
        new["x" if draw(st.booleans()) else "y"] = draw(st.sampled_from([-1.0, 1.0])) * 1e6
    if fault in ("overlap", "home_covered", "landmark_outside"):
        spec["landmarks"].append(new)
        return spec, f"landmarks[{n}]"
    if fault == "home_outside":
        k = draw(st.integers(0, 1))
        spec["home"][k] = draw(st.one_of(st.floats(max_value=arena[k]), st.floats(min_value=arena[k + 2])))
        return spec, "home"
    if fault == "arena_order":
        k = draw(st.integers(0, 1))
        spec["arena"][k + 2] = arena[k] - draw(st.floats(0.0, 1e4))
        return spec, "arena"
    if fault == "arena_shape":
        return {
            **spec,
            "arena": draw(st.lists(st.floats(0, 1), max_size=6).filter(lambda v: len(v) != 4) | JUNK),
        }, "arena"
    if fault == "no_landmarks":
        return {**spec, "landmarks": draw(JUNK.filter(lambda v: not (isinstance(v, list) and v)))}, "landmarks"
    if fault == "missing":
        key = draw(st.sampled_from(["arena", "home", "landmarks"]))
        del spec[key]
        return spec, key
    if fault == "unknown":
        return {**spec, "colour": draw(JUNK)}, "colour"
    if fault == "lm_missing":
        key = draw(st.sampled_from("xyr"))
        del spec["landmarks"][i][key]
        return spec, f"landmarks[{i}].{key}"
    if fault == "lm_unknown":
        spec["landmarks"][i]["z"] = 1.0
        return spec, f"landmarks[{i}].z"
    if fault == "lm_type":
        spec["landmarks"][i] = draw(JUNK.filter(lambda v: not isinstance(v, dict)))
        return spec, f"landmarks[{i}]"
    if fault == "name":
        return {**spec, "name": draw(JUNK.filter(lambda v: not (isinstance(v, str) and v)))}, "name"
    return draw(st.one_of(st.lists(st.integers(), max_size=2), st.text(max_size=3), st.none())), "environment"


@settings(max_examples=300, **FAST)
@given(case=broken_specs())
def test_an_invalid_environment_is_an_input_error_naming_the_field(case, tmp_path_factory):
    spec, field = case
    with pytest.raises(InputError) as exc:
        env_from_dict(spec)
    named = exc.value.field  # "home" may be named as its number "home[0]" (e.g. -inf)
    assert named in (field, *(f"{field}[{k}]" for k in range(4))), (spec, str(exc.value))
    assert str(exc.value).startswith(f"{named}: ")
    path = tmp_path_factory.getbasetemp() / "broken.json"
    path.write_text(json.dumps(spec))  # the same through a file (NaN and huge integers survive JSON)
    with pytest.raises(InputError) as exc:
        load_env(path)
    assert exc.value.field == named, (spec, str(exc.value))


@settings(max_examples=80, **FAST)
@given(
    landmarks=st.one_of(st.just([(200.0, 200.0, 20.0)]), JUNK, st.lists(st.lists(st.floats(), max_size=4), max_size=3)),
    home=st.one_of(st.just((500.0, 500.0)), st.just(np.array([500, 500], np.float32)), JUNK),
    arena=st.one_of(st.just((0.0, 0.0, 1000.0, 1000.0)), st.just(np.array([0, 0, 1000, 1000])), JUNK),
    pad_to=st.one_of(st.none(), st.integers(-2, 3), JUNK, st.sampled_from([2.5, 10**6, 2**63])),
)
def test_make_env_builds_an_env_or_names_the_argument(landmarks, home, arena, pad_to):
    try:
        with hints_unchecked():  # junk of every type on purpose: make_env's own errors are tested
            env = delvjax.make_env(landmarks, home=home, arena=arena, pad_to=pad_to)
    except InputError as exc:
        assert exc.field.split("[")[0].split(".")[0] in {"landmarks", "home", "arena", "pad_to"}, str(exc)
        return
    assert env.landmarks.shape[0] == (env.n_landmarks if pad_to is None else pad_to)


JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.floats() | st.integers() | st.text(max_size=3),
    lambda kids: (
        st.lists(kids, max_size=3)
        | st.dictionaries(st.sampled_from(["arena", "home", "landmarks", "name", "x", "y", "r"]), kids, max_size=4)
    ),
    max_leaves=12,
)


@settings(max_examples=80, **FAST)
@given(content=st.one_of(JSON_VALUES.map(json.dumps).map(str.encode), st.binary(max_size=30)))
@example(content=b"[" * 100_000)  # nesting deeper than the JSON decoder's recursion limit
@example(content=b'{"arena": [' + b"1" * 5000 + b", 0, 1, 1]}")  # more digits than int() converts
def test_any_file_is_an_environment_or_an_input_error(content, tmp_path_factory):
    path = tmp_path_factory.getbasetemp() / "any.json"
    path.write_bytes(content)
    try:
        assert isinstance(load_env(path), delvjax.Env)
    except InputError as exc:
        assert str(exc).startswith(f"{exc.field}: ")
