#!/usr/bin/env bash
# Table 1 of Francu et al. 2021 (time of the quasi-static experiments, standard against
# mixed): runs each built-in scene with the paper's E, nu and steps, `standard` and
# `mixed-p1`, with fixed load steps (one solve per step, as the paper), and prints our
# seconds, Newton iterations and whether every step converged beside the paper's seconds
# (theirs: a 4-core i7-3770; their tolerances differ from ours, which are the solver's).
# The pressures are the scenes' own (Table 1's). A scene `isochor list` does not show is
# skipped, and said so.
#
#   scripts/table-1.sh              # builds the release binary with cargo, then runs
#   ISOCHOR=path/to/isochor scripts/table-1.sh
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ -z "${ISOCHOR:-}" ]]; then
    cargo build --release --quiet --manifest-path "$root/Cargo.toml" -p isochor-scenes --bin isochor
    ISOCHOR="${CARGO_TARGET_DIR:-$root/target}/release/isochor"
fi
scenes="$("$ISOCHOR" list)"

# One run: prints "seconds iterations converged" from the run's summary (nothing if the
# scene could not be run).
run() {
    local scene=$1 variant=$2
    shift 2
    local sets=() s summary
    for s in "$@"; do sets+=(--set "$s"); done
    # A run that does not converge exits with 3 and still prints its summary.
    summary="$("$ISOCHOR" run "$scene" --variant "$variant" --set increments=fixed "${sets[@]}" \
        </dev/null 2>/dev/null)" || true
    if [[ -n "$summary" ]]; then
        echo "$(field 'wall time' "$summary") $(field 'newton iterations' "$summary") $(field converged "$summary")"
    fi
}

# The first word after the label $1 in the summary $2.
field() {
    sed -n "s/^$1 *\([^ ]*\).*$/\1/p" <<<"$2"
}

# Seconds (s), Newton iterations and converged, of `standard` and `mixed-p1`.
format='%-19s %-6s %-11s %-6s %-6s | %-9s %-9s | %-8s %-5s %-4s | %-8s %-5s %-4s\n'
printf "$format" experiment E_kPa nu steps p_kPa paper_std paper_mix \
    std_s iters conv mixed_s iters conv
# experiment | scene | E (Pa) | nu standard | nu mixed | steps standard | steps mixed | p (kPa,
# the scene's) | the paper's seconds, standard | mixed
while IFS='|' read -r name scene young nu_s nu_m steps_s steps_m pressure paper_s paper_m; do
    if ! grep -qx "$scene" <<<"$scenes"; then
        echo "$name: skipped, no built-in scene '$scene' in this isochor"
        continue
    fi
    read -r s_time s_iterations s_converged <<<"$(run "$scene" standard "E=$young" "nu=$nu_s" "steps=$steps_s")"
    read -r m_time m_iterations m_converged <<<"$(run "$scene" mixed-p1 "E=$young" "nu=$nu_m" "steps=$steps_m")"
    nu="$nu_s"; [[ "$nu_s" == "$nu_m" ]] || nu="$nu_s/$nu_m"
    steps="$steps_s"; [[ "$steps_s" == "$steps_m" ]] || steps="$steps_s/$steps_m"
    printf "$format" "$name" "$((young / 1000))" "$nu" "$steps" "$pressure" "$paper_s" "$paper_m" \
        "${s_time:-error}" "${s_iterations:--}" "${s_converged:--}" \
        "${m_time:-error}" "${m_iterations:--}" "${m_converged:--}"
done <<'ROWS'
Inflated tube|inflated-tube|90000|0.499|0.499|10|10|10|9|19
Hanging spine 1|spine-arm|266000|0.499|0.499|10|10|-|3|4
Hanging spine 2|spine-arm|150000|0.4999|0.4999|20|10|-|2|2.5
Cushion|cushion|90000|0.499|0.499|10|10|10|2|3
Bubble|bubble|100000|0.499|0.499|10|10|4|12|27
Finger|finger|100000|0.499|0.499|10|10|10|28|62
Compressed box|compressed-block|66000|0.4999|0.4999|10|10|15|102|12
Stretched cylinder|stretched-cylinder|66000|0.49|0.4999|80|20|-|106|78
Twisted box|twisted-box|66000|0.45|0.45|20|10|-|68|60
ROWS
