#!/usr/bin/env bash
# The engines' convergence to the reference on stacks of N = 3 and N = 6 blocks (issue 23;
# docs/engines.md, "N blocks"): for every built engine and time step dt in 1e-3, 1e-4, 1e-5 s,
# `rockbench compare SCENE --engines NAME --quick --set NAME.time_step=DT` on two free-rocking
# columns of the drums of scenes/column_6_drums.toml (marble, 0.85 m tall, 0.96 to 0.86 m wide):
#   - 3 drums (the column's first three) released together from half the locked 3-drum column's
#     critical angle (0.18320 rad = atan(0.48 / 1.25089) / 2), the top drum from 0.19 rad: it
#     lands on the drum below at 0.042 s, then the column rocks as one body; 4 s, 23 impacts;
#   - 6 drums released together from half the locked 6-drum column's critical angle (0.097075
#     rad = atan(0.48 / 2.44118) / 2): the column rocks as one body; 5 s, 4 ground impacts. (The
#     top drum released any further, even by 2.5e-5 rad, leaves the model within 4 ms: its
#     landing has no admissible outcome, docs/n-blocks.md "Where the model ends".)
# Prints one Markdown table per stack: the largest angle error over the blocks (and the worst
# block), the impacts matched, the order per decade of dt, and the engine's wall seconds per
# simulated second at dt 1e-4 s. An engine that fails a run prints its error. Every run's folder
# stays under the output folder.
#
# Usage: scripts/nblock-convergence.sh [--out DIR] [--engines a,b] [--steps "1e-3 1e-4"]
#        (DIR default: out/nblock-convergence; engines: every built one)
# Environment: ROCKBENCH_BUILD_DIR (default build). Needs jq and awk.
# Took about 12 minutes for Bullet, ODE, MuJoCo and DART and about 40 for Siconos alone on the
# shared 2-core machine under load (2026-11-26): the runs at 1e-5 s are most of it.
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/nblock-convergence
engines=""
steps="1e-3 1e-4 1e-5"
while [ $# -gt 0 ]; do
  case "$1" in
    --out | --engines | --steps)
      [ $# -ge 2 ] || { echo "nblock-convergence.sh: $1 needs a value" >&2; exit 2; }
      case "$1" in
        --out) out=$2 ;;
        --engines) engines=$2 ;;
        --steps) steps=$2 ;;
      esac
      shift
      ;;
    -h | --help)
      awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"
      exit 0
      ;;
    *)
      echo "nblock-convergence.sh: unknown argument '$1'" >&2
      exit 2
      ;;
  esac
  shift
done

rockbench=${ROCKBENCH_BUILD_DIR:-build}/src/cli/rockbench
[ -x "$rockbench" ] || { echo "nblock-convergence.sh: no $rockbench (scripts/build.sh)" >&2; exit 2; }
if [ -z "$engines" ]; then
  engines=$("$rockbench" engines | awk -F: '$1 != "reference" && $1 != "mpi" && $2 !~ /left out/ { printf "%s%s", sep, $1; sep = "," }')
fi
mkdir -p "$out"

# drums N THETA TOP DURATION: a scene of the first N drums of scenes/column_6_drums.toml.
drums() {
  local n=$1 theta=$2 top=$3 duration=$4
  local widths=(0.96 0.94 0.92 0.90 0.88 0.86) thetas="" omegas=""
  echo "title = \"$n marble drums released from $theta rad, the top one from $top, free rocking\""
  for ((i = 0; i < n; i++)); do
    printf '[[block]]\nwidth = %s\nheight = 0.85\ndensity = 2700.0\ndepth = %s\n' \
      "${widths[$i]}" "${widths[$i]}"
    local t=$theta
    [ "$i" -eq $((n - 1)) ] && t=$top
    thetas="$thetas${thetas:+, }$t"
    omegas="$omegas${omegas:+, }0.0"
  done
  printf '[initial]\ntheta = [%s]\nomega = [%s]\n' "$thetas" "$omegas"
  printf '[run]\nduration = %s\noutput_interval = 0.005\n' "$duration"
}
drums 3 0.18320 0.19 4.0 >"$out/drums_3.toml"
drums 6 0.097075 0.097075 5.0 >"$out/drums_6.toml"

for stack in 3 6; do
  scene=$out/drums_$stack.toml
  duration=$(awk -F' *= *' '$1 == "duration" { print $2 }' "$scene")
  echo
  echo "$stack drums: $(head -1 "$scene" | sed 's/^title = //')"
  echo
  echo "| engine | dt 1e-3 s | dt 1e-4 s | dt 1e-5 s | order (per decade) | wall s / simulated s at 1e-4 |"
  echo "|---|---|---|---|---|---|"
  IFS=, read -r -a list <<<"$engines"
  for engine in "${list[@]}"; do
    row="| $engine"
    errors=()
    wall=""
    refusal=""
    for dt in $steps; do
      dir=$out/drums_${stack}_${engine}_$dt
      if ! "$rockbench" compare "$scene" --engines "$engine" --quick \
        --set "$engine.time_step=$dt" --out "$dir" >"$dir.out" 2>&1; then
        # An engine that fails the stack does so at every step: its words, once.
        refusal=$(grep -o "engine $engine: .*" "$dir.out" | head -1)
        [ -n "$refusal" ] || refusal="failed: $(tail -1 "$dir.out")"
        break
      fi
      # The worst block's max error, which block, the impacts matched of the reference's.
      cell=$(jq -r --arg e "$engine" '
        .engines[$e] as $a
        | [range(1; 1 + ([$a | keys[] | select(test("^theta[0-9]+$"))] | length))
           | {k: ., err: $a["theta\(.)"].max_abs_error_rad}]
        | max_by(.err) as $w
        | "\($w.err) \($w.k) \($a.impacts_matched) \($a.impacts_reference) \($a.wall_s) \($a.status)"
        ' "$dir/comparison.json")
      read -r err block matched reference wall_s status <<<"$cell"
      errors+=("$err")
      text=$(printf '%.2g rad (theta%s; %s of %s)' "$err" "$block" "$matched" "$reference")
      [ "$status" = completed ] || [ "$status" = at_rest ] || text="$text, $status"
      row="$row | $text"
      [ "$dt" = 1e-4 ] && wall=$(awk -v w="$wall_s" -v d="$duration" 'BEGIN { printf "%.2g", w / d }')
    done
    if [ -n "$refusal" ]; then
      echo "| $engine | $refusal | | | - | - |"
      continue
    fi
    orders=""
    for ((k = 1; k < ${#errors[@]}; k++)); do
      a=${errors[$((k - 1))]} b=${errors[$k]}
      if [ -n "$a" ] && [ -n "$b" ]; then
        o=$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f", log(a / b) / log(10) }')
      else
        o="-"
      fi
      orders="$orders${orders:+, }$o"
    done
    echo "$row | $orders | ${wall:--} |"
  done
done
