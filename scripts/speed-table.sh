#!/usr/bin/env bash
# Speed against accuracy: the time isochor takes to reach the error it reaches on the
# cantilever (truth 37.38 mm), the compressed block (truth 20.99 mm at nu = 0.4999) and the
# inflated tube, per discretization, with the phase split of each run (docs/performance.md,
# "Speed against accuracy"). Each row is the fastest of REPEATS runs (default 3) of the
# release build; RAYON_NUM_THREADS is passed through (set it to 1 for one thread).
#
#   scripts/speed-table.sh                 # every row
#   RAYON_NUM_THREADS=1 scripts/speed-table.sh cantilever
#   scripts/speed-table.sh cantilever --set solver.jacobian=modified   # extra --set for every run
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked --quiet -p isochor-scenes --bin isochor
bin=target/release/isochor
repeats=${REPEATS:-3}
only=${1:-all}
shift || true
extra=("$@")

echo "threads: ${RAYON_NUM_THREADS:-default}; load average: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%F)"
echo
echo "| scene | method | element | res | unknowns | value | error | iterations | factorizations | total | model | setup | assembly | factorization | solve | line search |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"

# row SCENE PROBE TRUTH METHOD ELEMENT RES [--set ...]: one line of the table.
row() {
  local scene=$1 probe=$2 truth=$3 method=$4 element=$5 res=$6
  shift 6
  local runs=()
  for _ in $(seq "$repeats"); do
    runs+=("$("$bin" run "$scene" --json --set "method=$method" --set "element=$element" \
      --set "res=$res" "$@" ${extra[@]+"${extra[@]}"})")
  done
  printf '%s\n' "${runs[@]}" | python3 -c '
import json, sys
scene, probe, truth, res = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
runs = [json.loads(line) for line in sys.stdin if line.strip()]
best = min(runs, key=lambda r: r["timings"]["model_s"] + r["wall_time_s"])
t = best["timings"]
value = best["probes"][probe]
error = "-" if truth == "-" else "%+.2f%%" % (100 * (value / float(truth) - 1))
ms = lambda s: "%.3f s" % s
print("| %s | %s | %s | %s | %s | %.6g | %s | %d | %d | %s | %s | %s | %s | %s | %s | %s |" % (
    scene, best["method"], best["element"], res, format(best["dofs"], ","), value, error,
    best["newton_iterations"], t["factorizations"], ms(t["model_s"] + best["wall_time_s"]),
    ms(t["model_s"]), ms(t["setup_s"]), ms(t["assembly_s"]), ms(t["factorization_s"]),
    ms(t["solve_s"]), ms(t["line_search_s"])))
' "$scene" "$probe" "$truth" "$res"
}

if [ "$only" = all ] || [ "$only" = cantilever ]; then
  for res in 2 3 4; do row cantilever tip_deflection 0.03738 mixed-p0 tet10 "$res"; done
  for res in 2 6; do row cantilever tip_deflection 0.03738 mixed-p1 tet10 "$res"; done
fi
if [ "$only" = all ] || [ "$only" = compressed-block ]; then
  for res in 4 8; do
    row compressed-block top_center_deflection 0.02099 mixed-p0 tet10 "$res"
    row compressed-block top_center_deflection 0.02099 mixed-p1 tet10 "$res"
  done
fi
if [ "$only" = all ] || [ "$only" = inflated-tube ]; then
  for res in 1 2; do row inflated-tube mean_radius_increase - mixed-p1 tet10 "$res"; done
fi
