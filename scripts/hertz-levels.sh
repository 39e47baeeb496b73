#!/usr/bin/env bash
# Hertz contact over refinement (docs/validation.md, "Hertz contact"): runs the
# `hertz_study_level` test of validation/tests/hertz.rs (release) once per mesh level, each in
# a process of its own under `/usr/bin/time -v` (wall time and peak memory of that level
# alone), keeps each level's log in DIR, then prints the force error per frame and level, the
# observed order and Richardson limit over the last three levels and the fitted finite-sphere
# compliance C (scripts/hertz-richardson.py).
#
#   scripts/hertz-levels.sh tet4 mixed-p1 8 10 12          # logs in target/hertz
#   HERTZ_LOGS=DIR scripts/hertz-levels.sh tet10 mixed-p1 4 6 8
#   scripts/hertz-levels.sh --table tet4 mixed-p1 8 10 12  # only the table, from the logs
set -euo pipefail
cd "$(dirname "$0")/.."
run=true
if [ "${1:-}" = "--table" ]; then
    run=false
    shift
fi
element=$1
method=$2
shift 2
logs=${HERTZ_LOGS:-target/hertz}
mkdir -p "$logs"
if $run; then
    cargo test --release --locked -p isochor-validation --test validation --no-run 2>/dev/null
    for res in "$@"; do
        log="$logs/$element-$method-$res.log"
        echo "res $res: load average $(cut -d' ' -f1-3 /proc/loadavg) at start, $(date -u '+%F %T') UTC" >"$log"
        HERTZ_ELEMENT=$element HERTZ_METHOD=$method HERTZ_RES=$res /usr/bin/time -v \
            cargo test --release --locked -p isochor-validation --test validation -q -- \
            --ignored --exact hertz::hertz_study_level --nocapture >>"$log" 2>&1
        echo "res $res: load average $(cut -d' ' -f1-3 /proc/loadavg) at end, $(date -u '+%F %T') UTC" >>"$log"
    done
fi
logfiles=()
for res in "$@"; do
    logfiles+=("$logs/$element-$method-$res.log")
done
python3 scripts/hertz-richardson.py "${logfiles[@]}"
