#!/usr/bin/env bash
# Wall time per step of the built-in contact scenes with surface contact and the same scene
# with it switched off (docs/contact.md, "Speed"): the scene as `isochor show` prints it,
# its `[contact]` tables removed (no `--set` key removes a table). Release build; each row
# is the fastest of REPEATS runs (default 3); the phases (ms per step) are the `--json`
# report's `timings`.
#
#   scripts/contact-speed.sh                        # every row
#   scripts/contact-speed.sh colliding-balls --set frames=4   # one scene, extra --set
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked --quiet -p isochor-scenes --bin isochor
bin=$PWD/target/release/isochor
repeats=${REPEATS:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The scene of `isochor show ARGS` without its `[contact]` and `[[contact.*]]` tables.
without_contact() {
    "$bin" show "$@" | awk '
        /^\[\[?contact[].]/ { skip = 1; next }
        /^\[/ { skip = 0 }
        !skip' >"$tmp/off.toml"
}

# One row: LABEL CONTACT(on/off) SCENE-ARGS...; the fastest of the repeats.
row() {
    local label=$1 contact=$2
    shift 2
    local args=("$@")
    if [ "$contact" = off ]; then
        without_contact "${args[@]}"
        args=("$tmp/off.toml")
    fi
    local load
    load=$(cut -d' ' -f1-3 /proc/loadavg)
    : >"$tmp/runs.jsonl"
    for _ in $(seq "$repeats"); do
        "$bin" run "${args[@]}" --json 2>/dev/null >>"$tmp/runs.jsonl"
    done
    python3 - "$label" "$contact" "$load" "$tmp/runs.jsonl" <<'PY'
import json, sys
label, contact, load, path = sys.argv[1:5]
text, decoder, runs, i = open(path).read(), json.JSONDecoder(), [], 0
while text[i:].strip():
    i += len(text[i:]) - len(text[i:].lstrip())
    run, i = decoder.raw_decode(text, i)
    runs.append(run)
r = min(runs, key=lambda r: r["wall_time_s"])
t, n = r["timings"], r["steps"]
ms = lambda s: f"{1e3 * s / n:.1f}"
per_iteration = f"{1e3 * r['wall_time_s'] / r['newton_iterations']:.1f}"
phases = [ms(t[k]) for k in ("setup_s", "assembly_s", "factorization_s", "solve_s", "line_search_s")]
cells = [label, contact, f"{r['tets']:,}", f"{n} ({r['cuts']} cut)", str(r["newton_iterations"]),
         ms(r["wall_time_s"]), per_iteration] + phases + [str(r["converged"]).lower(), load]
print("| " + " | ".join(cells) + " |")
PY
}

echo "release; $(date -u +%F); threads ${RAYON_NUM_THREADS:-default}; the fastest of $repeats runs"
echo "| scene | contact | tets | steps | Newton iterations | ms per step | ms per Newton iteration | setup | assembly | factorization | solve | line search | converged | load average at start |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|"
if [ $# -gt 0 ]; then
    row "$*" on "$@"
    row "$*" off "$@"
    exit
fi
row "colliding-balls, first 4 steps (before impact)" on colliding-balls --set frames=4
row "colliding-balls, first 4 steps (before impact)" off colliding-balls --set frames=4
row "colliding-balls" on colliding-balls
row "colliding-balls (the balls pass through each other)" off colliding-balls
row "grasp" on grasp
row "grasp (the pads pass through the cylinder)" off grasp
row "finger-volume --variant self-contact" on finger-volume --variant self-contact
row "finger-volume --variant self-contact (walls may cross)" off finger-volume --variant self-contact
