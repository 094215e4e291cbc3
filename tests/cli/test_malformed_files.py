"""Random malformed input files (hypothesis; docs/reliability.md): sweep TOML, database CSV and YAML,
environment JSON. Each reader returns its result or raises `InputError` (what the command line prints as
one line, exit 2); nothing else escapes, and reading writes nothing."""

from __future__ import annotations

import json
import math
import tempfile
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from delvjax.core.errors import InputError
from delvjax.envs._presets import load_env
from delvjax.images._disk import ENTRIES, METADATA, read_index
from delvjax.sweeps._examples import EXAMPLE
from delvjax.sweeps._file import read_sweep
from tests.cases.strategies import FAST, JUNK

TEXTS = st.text(alphabet=st.characters(codec="utf-8"), max_size=12)
VALUES = st.one_of(
    JUNK,
    TEXTS,
    st.floats(),
    st.integers(-(2**70), 2**70),
    st.dictionaries(TEXTS, JUNK, max_size=2),
    st.lists(st.lists(st.one_of(st.integers(), TEXTS), max_size=2), max_size=2),  # nested lists
)
HEADER = "X [mm],Y [mm],Z [mm],Heading [degrees],Filename,Grid X,Grid Y,Grid Z"  # a compact BoB header (no Pitch, Roll)
ROW = "{x},{y},0,0,image_{i}.png,{i},0,0"
METADATA_BLOCK = {
    "arena_cm": [0, 0, 180, 180],
    "home_cm": [90, 90],
    "spacing_cm": 20,
    "camera_height_cm": 25,
    "elevation_deg": [30, -30],
    "panorama": [60, 360],
    "obstacles": {"cylinders": [[45, 135, 8]], "boxes": []},
}


def toml_value(v) -> str:
    """`v` written as TOML (lists, tables, strings, numbers; non-finite floats as TOML's nan/inf)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {toml_value(x)}" for k, x in v.items()) + "}"
    if v is None:
        return '""'
    return "[" + ", ".join(toml_value(x) for x in v) + "]"


def refused_or_read(read, path: Path) -> None:
    before = sorted(path.parent.iterdir())
    try:
        read(path)
    except InputError:
        pass
    assert sorted(path.parent.iterdir()) == before  # reading wrote nothing


@settings(max_examples=80, **FAST)
@given(
    line=st.integers(0, 40),
    key=st.sampled_from(["d", "env", "method", "seed", "metrics", "kind", "spacing", "bearing_noise_deg", "levels"]),
    value=VALUES,
    cut=st.one_of(st.none(), st.integers(0, 2000)),
)
def test_a_mutated_sweep_file_is_read_or_refused(line, key, value, cut):
    lines = EXAMPLE.splitlines()
    lines.insert(min(line, len(lines)), f"{key} = {toml_value(value)}")
    text = "\n".join(lines)[:cut] if cut is not None else "\n".join(lines)
    with tempfile.TemporaryDirectory() as d:
        (Path(d) / "s.toml").write_text(text)
        refused_or_read(read_sweep, Path(d) / "s.toml")


@settings(max_examples=80, **FAST)
@given(
    rows=st.lists(
        st.lists(st.one_of(st.sampled_from(["", "1", "nan", "x", "1e400", '"a,b"']), TEXTS), max_size=10), max_size=4
    ),
    bom=st.booleans(),
    field=st.sampled_from([None, *METADATA_BLOCK]),
    value=VALUES,
)
def test_a_mutated_database_index_is_read_or_refused(rows, bom, field, value):
    good = [ROW.format(x=900 + 200 * i, y=900, i=i) for i in range(3)]
    text = "\n".join([HEADER, *good, *(",".join(r) for r in rows)]) + "\n"
    meta = dict(METADATA_BLOCK)
    if field is not None:
        meta[field] = value
    with tempfile.TemporaryDirectory() as d:
        folder = Path(d) / "db"
        folder.mkdir()
        (folder / ENTRIES).write_text(("\ufeff" if bom else "") + text, encoding="utf-8")
        try:
            dumped = yaml.safe_dump({"metadata": {"delvjax": meta}})
        except yaml.YAMLError:
            return
        (folder / METADATA).write_text("%YAML:1.0\n---\n" + dumped)
        refused_or_read(lambda p: read_index(p.parent), folder / ENTRIES)


@settings(max_examples=80, **FAST)
@given(
    field=st.sampled_from(["name", "arena", "home", "landmarks", "x", "r", "extra"]),
    value=VALUES,
    cut=st.one_of(st.none(), st.integers(0, 200)),
)
def test_a_mutated_environment_file_is_read_or_refused(field, value, cut):
    env = {"name": "e", "arena": [0, 0, 1000, 1000], "home": [500, 500], "landmarks": [{"x": 200, "y": 200, "r": 20}]}
    if field in ("x", "r"):
        env["landmarks"][0][field] = value
    else:
        env[field] = value
    try:
        text = json.dumps(env)
    except (TypeError, ValueError):
        return
    with tempfile.TemporaryDirectory() as d:
        (Path(d) / "e.json").write_text(text[:cut] if cut is not None else text)
        refused_or_read(load_env, Path(d) / "e.json")


def test_an_integer_beyond_float_range_is_refused_not_overflowed():
    """Found by the mutation test above (1 run in ~20): `spacing_cm: 10**400` raised OverflowError from
    math.isfinite instead of InputError; a sweep range's bounds had the same escape."""
    with tempfile.TemporaryDirectory() as d:
        folder = Path(d) / "db"
        folder.mkdir()
        good = [ROW.format(x=900 + 200 * i, y=900, i=i) for i in range(3)]
        (folder / ENTRIES).write_text("\n".join([HEADER, *good]) + "\n", encoding="utf-8")
        meta = dict(METADATA_BLOCK, spacing_cm=10**400)
        (folder / METADATA).write_text("%YAML:1.0\n---\n" + yaml.safe_dump({"metadata": {"delvjax": meta}}))
        with pytest.raises(InputError, match="spacing_cm"):
            read_index(folder)
        text = EXAMPLE.replace("[axes]", "[axes]\nturn_noise_deg = {start = " + str(10**400) + ", stop = 1}", 1)
        (Path(d) / "s.toml").write_text(text)
        with pytest.raises(InputError, match="axes.turn_noise_deg"):
            read_sweep(Path(d) / "s.toml")
