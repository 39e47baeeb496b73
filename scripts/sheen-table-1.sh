#!/usr/bin/env bash
# Table 1 of Sheen et al. 2021 (per-frame time and iterations of the soft-tissue examples):
# runs each row's built-in scene and variant and prints, as a Markdown table, our seconds and
# Newton iterations per frame (every attempt, cut ones included, over the frames asked for)
# and the volume change at the end, beside the paper's seconds and Ipopt iterations per frame
# (theirs: Ipopt on their hardware; meshes, frame counts and solvers differ). A run that
# stops early says at which step. The fine ball (400 frames of 63,888 tets, about an hour)
# runs only with FINE_BALL=1.
#
#   scripts/sheen-table-1.sh                 # builds the release binary with cargo, then runs
#   ISOCHOR=path/to/isochor scripts/sheen-table-1.sh
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ -z "${ISOCHOR:-}" ]]; then
    cargo build --release --quiet --manifest-path "$root/Cargo.toml" -p isochor-scenes --bin isochor
    ISOCHOR="${CARGO_TARGET_DIR:-$root/target}/release/isochor"
fi

# One table row from a run's JSON summary (stdin) and the row's label and paper values.
format_row='
import json, sys
row, paper_s, paper_it = sys.argv[1:4]
d = json.load(sys.stdin)
frames = max(d["steps_requested"], 1)
steps, cuts, failed = d["steps"], d["cuts"], d["failed_step"]
run = f"{steps} steps, {cuts} cuts" if d["converged"] else f"stopped at step {failed} ({steps} accepted)"
seconds = d["wall_time_s"] / frames
iterations = d["newton_iterations"] / frames
change = 100 * d["volume_change"]
print(f"| {row} | {paper_s} | {paper_it} | {seconds:.3g} | {iterations:.3g} | {change:+.3g}% | {run} |")
'

echo "| row | paper s / frame | paper it. / frame | ours s / frame | Newton it. / frame | volume change | run |"
echo "|---|---|---|---|---|---|---|"
# row | scene | variant | settings (space separated) | paper's seconds | paper's iterations
while IFS='|' read -r row scene variant settings paper_s paper_it; do
    if [[ $scene == ball-drop && ${FINE_BALL:-0} != 1 ]]; then
        continue
    fi
    sets=()
    for s in $settings; do sets+=(--set "$s"); done
    json=$("$ISOCHOR" run "$scene" --variant "$variant" "${sets[@]}" --json </dev/null 2>/dev/null) || true
    if [[ -z $json ]]; then
        echo "| $row | $paper_s | $paper_it | error | | | |"
        continue
    fi
    python3 -c "$format_row" "$row" "$paper_s" "$paper_it" <<<"$json"
done <<'ROWS'
Cloth-Body, SNH lambda 400|garment|snh-400||12.10|21.32
Cloth-Body, SNH lambda 40|garment|snh-40||12.93|23.09
Cloth-Body, ours lambda 120, beta 6|garment|ours-120||12.82|17.98
Cloth-Body, ours lambda 120, beta 6, lambda_e 100|garment|ours-120-epidermis||14.63|19.18
Puck, SNH lambda 40|bulge-puck|standard-0.4545|model=stable-neo-hookean steps=50|1.55|3.00
Puck, SNH lambda 400|bulge-puck|standard-0.495|model=stable-neo-hookean steps=50|1.58|3.14
Puck, ours beta 0|bulge-puck|zonal|beta=0 steps=50|2.25|4.00
Puck, ours beta 9|bulge-puck|zonal|steps=50|1.93|3.38
Puck, ours beta 9, lambda_e 100|bulge-puck|zonal-epidermis|steps=50|2.25|3.51
Ball (fine), ours|ball-drop|zonal||17.91|12.29
Ball (coarse), NH lambda 144|ball-drop-coarse|standard-0.45||1.81|15.08
Ball (coarse), NH lambda 1584|ball-drop-coarse|standard-0.495||2.50|21.84
Ball (coarse), ours|ball-drop-coarse|zonal||2.71|22.10
Armadillo, SNH lambda 400|squeezed-creature|snh-400||6.26|11.29
Armadillo, ours|squeezed-creature|ours||6.97|10.84
Stretch, SNH lambda 40|stretch-cube|snh-40||2.80|4.51
Stretch, SNH lambda 400|stretch-cube|snh-400||9.91|14.33
Stretch, ours beta 0|stretch-cube|ours-beta-0||7.89|9.92
Stretch, ours beta 1|stretch-cube|ours-beta-1||7.28|9.24
Stretch, ours beta 1, lambda_e 10|stretch-cube|ours-beta-1-epidermis||6.25|7.33
Twist, SNH lambda 100|twist-cube|snh-100||86.06|138.33
Twist, ours without VC|twist-cube|ours-no-volume-constraint||37.32|50.33
Twist, ours|twist-cube|ours||62.15|90.33
Twist, ours lambda_e 15|twist-cube|ours-epidermis||103.10|92
ROWS
