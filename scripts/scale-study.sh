#!/usr/bin/env bash
# Scale study (issue "linear algebra at scale"): the cantilever box at growing `res`
# (24 res^3 tets: res 8 = 12k, 16 = 98k, 24 = 332k, 35 = 1.03M), one load step at
# nu = 0.4999, for each method and element given, with the scene's linear solver unless
# extra settings say otherwise. For each run it prints the tets, the unknowns (free
# displacement DOFs and pressures), the Newton iterations, the wall time of the solve, the
# time per Newton iteration (wall time over iterations: includes the one-off pattern and
# symbolic work) and the peak resident memory of the process (GNU time's maximum RSS), as
# a Markdown table and as CSV (scale-study.csv in the current folder), and the growth
# exponent of time and memory against tets (least squares on the log-log points of each configuration),
# and with matplotlib the log-log plot scale-study.png (scripts/scale-plot.py).
#
# A configuration stops growing after its first run that fails, runs out of its time
# limit (LIMIT seconds, default 1200) or needs more than MAX_RSS_GB (default 20) of memory.
#
#   scripts/scale-study.sh                                   # standard and mixed-p1, tet4
#   CONFIGS="mixed-p1/tet10" RES="1 2 3 4" scripts/scale-study.sh
#   EXTRA="--set linear=iterative" scripts/scale-study.sh    # the iterative path
#   ISOCHOR=path/to/isochor scripts/scale-study.sh
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ -z "${ISOCHOR:-}" ]]; then
    cargo build --release --quiet --manifest-path "$root/Cargo.toml" -p isochor-scenes --bin isochor
    ISOCHOR="${CARGO_TARGET_DIR:-$root/target}/release/isochor"
fi
configs=${CONFIGS:-"standard/tet4 mixed-p1/tet4"}
resolutions=${RES:-"4 8 12 16 20 24 28 35"}
limit=${LIMIT:-1200}
max_rss_kb=$(( ${MAX_RSS_GB:-20} * 1024 * 1024 ))
read -r -a extra <<<"${EXTRA:-}"

csv=scale-study.csv
echo "config,res,tets,unknowns,newton,converged,wall_s,per_iteration_s,peak_rss_mb" >"$csv"
echo "| config | res | tets | unknowns | Newton | converged | wall (s) | per iteration (s) | peak RSS (MB) |"
echo "|---|---|---|---|---|---|---|---|---|"
for config in $configs; do
    method=${config%/*}
    element=${config#*/}
    for res in $resolutions; do
        log=$(mktemp)
        status=0
        /usr/bin/time -f "%M" -o "$log.rss" timeout "$limit" "$ISOCHOR" run --json cantilever \
            --set method="$method" --set element="$element" --set res="$res" --set nu=0.4999 \
            --set steps=1 "${extra[@]}" </dev/null >"$log" 2>/dev/null || status=$?
        rss_kb=$(tail -n 1 "$log.rss")
        if [[ ! -s "$log" ]]; then
            echo "| $config | $res | | | | exit $status | > $limit | | $((rss_kb / 1024)) |"
            rm -f "$log" "$log.rss"
            break
        fi
        row=$(python3 - "$log" "$rss_kb" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
rss = int(sys.argv[2]) / 1024
its = max(d["newton_iterations"], 1)
print(d["tets"], d["dofs"], d["newton_iterations"], "yes" if d["converged"] else "no",
      f'{d["wall_time_s"]:.3g}', f'{d["wall_time_s"] / its:.3g}', f"{rss:.0f}")
EOF
)
        read -r tets dofs newton converged wall per rss <<<"$row"
        echo "| $config | $res | $tets | $dofs | $newton | $converged | $wall | $per | $rss |"
        echo "$config,$res,$tets,$dofs,$newton,$converged,$wall,$per,$rss" >>"$csv"
        rm -f "$log" "$log.rss"
        if [[ $converged != yes || $rss_kb -gt $max_rss_kb ]]; then
            break
        fi
    done
done

python3 - "$csv" <<'EOF'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("\n| config | wall-time exponent (t ~ tets^a) | peak-memory exponent |\n|---|---|---|")
for config in dict.fromkeys(r["config"] for r in rows):
    pts = [r for r in rows if r["config"] == config and int(r["tets"]) >= 10000]
    if len(pts) < 2:
        continue
    def slope(key):
        xs = [math.log(int(r["tets"])) for r in pts]
        ys = [math.log(float(r[key])) for r in pts]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    print(f"| {config} | {slope('wall_s'):.2f} | {slope('peak_rss_mb'):.2f} |")
EOF

if python3 -c "import matplotlib" 2>/dev/null; then
    python3 "$root/scripts/scale-plot.py" "$csv" scale-study.png
fi
