#!/usr/bin/env bash
# The headline benchmarks on whatever accelerator JAX finds (a GPU when the session has one; the CPU
# otherwise), in under 8 minutes (the parts' limits add up to 480 s), then one table: each benchmark's
# wall seconds and its key lines.
#
#     bash benchmarks/gpu.sh            # needs the project installed: pip install -e '.[test]'
#     GPU_PARTS="vector_map minwarping" bash benchmarks/gpu.sh   # only the parts named (a rerun)
#
# Each part runs under its own time limit, so one slow part cannot eat the others' time; a part that
# fails or times out is marked so in the table. Sizes: the vector map and catchment at the thesis grid
# (spacing 25 cm, 40 x 40), the image methods (warping, MFDID), a 1000-cell vector-map sweep and a 20-cell catchment
# sweep (1559 rollouts a cell) on one device,
# and `reproduce --quick` from an empty compilation cache, then again with nothing changed, and the
# MinWarping and 2D-Warping 40 x 40 maps (288 x 48 panoramas, 96 x 96 hypotheses), and a world ensemble
# (256 env1 members, DELV with compass, ACV, ALV, k = 0-2; benchmarks/bench_ensembles.py).
set -uo pipefail
cd "$(dirname "$0")/.."
# GPU_OUT, not OUT: the device tool sets OUT to the folder it sends back (at most 8 files), and
# `reproduce --quick` alone writes hundreds
OUT="${GPU_OUT:-$(mktemp -d)}"
mkdir -p "$OUT/logs"
# a bare accelerator machine: no `python` on PATH (only python3, a virtual environment's), no network, and
# JAX taking 75 % of the GPU's memory in each process (the sweep's two processes would not both fit)
if ! command -v python > /dev/null; then
  mkdir -p "$OUT/bin" && printf '#!/bin/sh\nexec %s "$@"\n' "$(command -v python3)" > "$OUT/bin/python"
  chmod +x "$OUT/bin/python" && export PATH="$OUT/bin:$PATH"
fi
if ! timeout -k 5 120 python -c "import delvjax.studies" 2> /dev/null \
  && ! timeout -k 5 120 python -m pip install -q --no-index --no-deps --no-build-isolation -e . > "$OUT/logs/install.txt" 2>&1; then
  # no install (an old setuptools without `wheel`): the source tree on the path, the studies where they install
  echo "pip could not install delvjax (see $OUT/logs/install.txt): running it from the source tree"
  [ -e delvjax/studies ] || ln -s ../studies delvjax/studies
  export PYTHONPATH="$PWD${PYTHONPATH:+:$PYTHONPATH}"
fi
export XLA_PYTHON_CLIENT_PREALLOCATE="${XLA_PYTHON_CLIENT_PREALLOCATE:-false}" PYTHONUNBUFFERED=1
# every step under `timeout -k`: a process stuck in a driver call ignores SIGTERM, and plain `timeout` then
# waits for it forever (suspected on 2026-12-04 on an H200: the script ran into the device call's limit
# with no line out; nothing came back to tell)
timeout -k 5 60 python -c "import jax; print('jax', jax.__version__, 'on', jax.devices()[0].platform, jax.devices()[0].device_kind)" \
  | tee "$OUT/logs/device.txt"

run() {  # name, time limit (s), command...; GPU_PARTS="a b" runs only the parts named
  local name=$1 limit=$2
  shift 2
  case " ${GPU_PARTS:-$name} " in *" $name "*) ;; *) return ;; esac
  local t0=$SECONDS
  timeout -k 10 "$limit" "$@" > "$OUT/logs/$name.txt" 2>&1
  local rc=$?
  echo "$name|$rc|$((SECONDS - t0))" >> "$OUT/parts.txt"
  echo "done: $name, exit $rc, $((SECONDS - t0)) s; last line: $(tail -1 "$OUT/logs/$name.txt")"  # progress as it comes
}

: > "$OUT/parts.txt"
run vector_map 60 python benchmarks/bench_vector_map.py --methods delv delv-compass alv acv --ref-points 10
run warping 40 python benchmarks/bench_warping.py
run catchment 50 python benchmarks/bench_rollouts.py --ref-points 4
run sweep 100 python benchmarks/bench_sweep.py --kinds vector-map catchment --devices 1 --processes \
  --cells 1000 --catchment-cells 20
run reproduce_quick 70 python benchmarks/bench_reproduce.py --quick --out "$OUT/reproduce"
run minwarping 100 python benchmarks/bench_minwarping.py --no-twin
# issue 52's GPU target is 256 members at the thesis's 25 cm grid: GPU_PARTS=ensembles_full in a call of its own
run ensembles 60 python benchmarks/bench_ensembles.py --members 256 --spacing 50 --families env1
case " ${GPU_PARTS:-} " in *" ensembles_full "*)
  run ensembles_full 420 python benchmarks/bench_ensembles.py --members 256 --spacing 25 ;;
esac
# issue 58's mesh views (ant eye and 360 x 90, benchmarks/bench_mesh.py): GPU_PARTS=mesh in a call of its own
case " ${GPU_PARTS:-} " in *" mesh "*)
  run mesh 120 python benchmarks/bench_mesh.py --twin-views 0 ;;
esac

echo
echo "| benchmark | exit | wall s | key lines |"
echo "|---|---|---|---|"
while IFS='|' read -r name rc secs; do
  status=$rc
  [ "$rc" = 124 ] && status="timeout"
  key=$(grep -E "ratio|warm|cold|second run|peak|x$|[0-9]x |device\(s\)|process\(es\)|^\| (minwarping|warping2d) |^ant eye|^360 x 90" "$OUT/logs/$name.txt" \
    | grep -v "^ *setting" | tail -4 | tr '\n' ';' | tr -s ' ')
  echo "| $name | $status | $secs | ${key:0:300} |"
done < "$OUT/parts.txt"
echo
echo "logs: $OUT/logs ($(cat "$OUT/logs/device.txt"))"
