"""Shared fixtures: random environments (seeded NumPy), the reproduce run (once per session, shared by
the pytest-xdist workers), image databases."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest

# Compiled programs go to the persistent cache of $DELVJAX_CACHE_DIR (as for the command line): the two
# pytest-xdist workers and the command-line subprocesses then compile a shared program once. CI points it
# at a fresh, empty folder (a cold run); "" disables it.
from delvjax.outputs._cache import enable_compilation_cache

enable_compilation_cache()

# The command-line subprocesses run on one device, as the workers do (the `delvjax` command's default is one
# per core on a CPU host, `cli._entry.host_devices`): they share the workers' one-device programs, and two
# workers already fill 2 cores. tests/cli/test_host_devices.py runs the default.
os.environ.setdefault("DELVJAX_DEVICES", "1")


@pytest.fixture(autouse=True, scope="module")
def programs_released_between_files():
    """A pytest worker compiles some 19,000 programs over the suite, about 3.4 memory mappings each while
    JAX caches them: past Linux's vm.max_map_count (65530) LLVM aborted the worker (two CI runs). After
    each file, past half the cap, JAX's in-memory caches are dropped (`release_programs_near_map_limit`)."""
    yield
    from delvjax.outputs._cache import release_programs_near_map_limit

    release_programs_near_map_limit()


@pytest.fixture(autouse=True)
def figures_a_reviewer_accepts():
    """Every figure delvjax writes during a test is checked as a reviewer would (`tests.cases.figures`:
    no overlapping texts, no text reaching into another panel, labelled axes on every data panel)."""
    from tests.cases.figures import recording_defects

    with recording_defects() as found:
        yield
    if found:
        pytest.fail(f"figures a reviewer would reject: {found}")


@pytest.fixture
def untyped():
    """A test that passes values of the wrong type on purpose: `tests.hints_unchecked` while it runs."""
    from tests import hints_unchecked

    with hints_unchecked():
        yield


ARENA = (0.0, 0.0, 1000.0, 1000.0)
HOME = (500.0, 500.0)


def random_landmarks(seed: int, n: int | None = None) -> np.ndarray:
    """3-6 non-overlapping cylinders (r 15-45 cm) in [150, 850]^2, none within r + 40 of home."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 7)) if n is None else n
    out: list[tuple[float, float, float]] = []
    while len(out) < n:
        x, y = rng.uniform(150, 850, size=2)
        r = rng.uniform(15, 45)
        if math.hypot(x - HOME[0], y - HOME[1]) < r + 40:
            continue
        if any(math.hypot(x - a, y - b) < r + c + 20 for a, b, c in out):
            continue
        out.append((float(x), float(y), float(r)))
    return np.array(out)


@pytest.fixture(scope="session")
def random_envs():
    """20 random environments as (landmarks array, delvjax Env), all padded to 6 landmarks
    and named alike so that they stack into one batched Env."""
    import delvjax

    return [(lm, delvjax.make_env(lm, name="random", pad_to=6)) for lm in (random_landmarks(s) for s in range(20))]


@pytest.fixture(scope="session")
def run(tmp_path_factory):
    """Every study once at the tiny size (`tests.cases.reproduce.TINY`): (output folder, result of
    reproduce(), seconds), for the files of tests/reproduce/, which run in name order; tests that
    change the folder put it back before they end. Under pytest-xdist the first worker to ask runs
    it into a folder the workers share and the others wait and take a copy of their own (one run of
    the studies per test session, however the files are dealt)."""
    import os
    import pickle
    import shutil
    import time

    from delvjax.reproduce import _run as reproduce
    from tests.cases.figures import recording_defects
    from tests.cases.reproduce import TINY

    own = tmp_path_factory.mktemp("reproduce") / "results"
    if os.environ.get("PYTEST_XDIST_WORKER") is None:
        t0 = time.perf_counter()
        with recording_defects() as found:
            result = reproduce.reproduce(own, config=TINY, progress=False)
        return own, {**result, "figure_defects": found}, time.perf_counter() - t0
    shared = tmp_path_factory.getbasetemp().parent / "reproduce-shared"  # the same folder for every worker
    done, failed = shared.with_suffix(".pickle"), shared.with_suffix(".failed")
    if failed.is_file():  # the run failed before (in this worker or another): say why, every time
        pytest.fail(f"the shared reproduce run failed:\n{failed.read_text()}")
    try:
        os.close(os.open(shared.with_suffix(".claimed"), os.O_CREAT | os.O_EXCL))  # the first worker runs it
    except FileExistsError:
        for _ in range(3600):  # the other workers wait for it (at most an hour)
            if failed.is_file():
                pytest.fail(f"the shared reproduce run failed in another worker:\n{failed.read_text()}")
            if done.is_file():
                break
            time.sleep(1.0)
    else:
        t0 = time.perf_counter()
        try:
            with recording_defects() as found:
                result = {**reproduce.reproduce(shared, config=TINY, progress=False), "figure_defects": found}
        except BaseException:
            import traceback

            failed.write_text(traceback.format_exc())
            raise
        tmp = done.with_suffix(".tmp")
        tmp.write_bytes(pickle.dumps((result, time.perf_counter() - t0)))
        tmp.replace(done)
    result, seconds = pickle.loads(done.read_bytes())
    shutil.copytree(shared, own)
    result["report"] = own / Path(result["report"]).relative_to(shared)
    return own, result, seconds


# --- image databases (images/test_disk.py, images/test_errors.py, images/test_cli.py) ----

from tests.cases.images_io import SEED, SMALL, entries, render_db, write_plain


@pytest.fixture(scope="module")
def default_db(tmp_path_factory) -> Path:
    """The robot world at the default size (360 x 60)."""
    return render_db(tmp_path_factory.mktemp("default") / "robot")


@pytest.fixture(scope="module")
def small_db(tmp_path_factory) -> Path:
    return render_db(tmp_path_factory.mktemp("small") / "robot", *SMALL, "--seed", str(SEED))


@pytest.fixture(scope="module")
def donut_db(tmp_path_factory) -> Path:
    return render_db(tmp_path_factory.mktemp("donut") / "robot", *SMALL, "--donut", "--seed", str(SEED))


@pytest.fixture(scope="module")
def plain_db(tmp_path_factory, small_db) -> Path:
    """The small database as a plain folder: shuffled rows, other file names, positions.csv in cm."""
    rows = entries(small_db)
    order = np.random.default_rng(0).permutation(len(rows))
    return write_plain(
        tmp_path_factory.mktemp("plain") / "panos",
        small_db,
        [rows[i] for i in order],
        rename=lambda i, f: f"pano {i:03d}.png",
    )


@pytest.fixture(scope="module")
def plain9(tmp_path_factory, small_db) -> Path:
    """A 3 x 3 plain folder (centre (90, 90)), the template the error cases break."""
    rows = [r for r in entries(small_db) if max(abs(float(r["X [mm]"]) - 900), abs(float(r["Y [mm]"]) - 900)) <= 200]
    assert len(rows) == 9
    return write_plain(tmp_path_factory.mktemp("plain9") / "nine", small_db, rows, rename=lambda i, f: f"p{i}.png")
