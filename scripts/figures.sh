#!/usr/bin/env bash
# Regenerates the README's headline figures into docs/figures/ (the SVGs only; each report
# folder under the output keeps every figure's gnuplot script and data for restyling):
#   - the work-precision figures (error against wall time, peak error against wall time) of a
#     full sweep of every built engine on scenes/housner_free_rocking.toml (one block),
#     scenes/thesis_free_rocking.toml and scenes/thesis_rinaldi228.toml;
#   - the angles and angle-error figures of the compare report of scenes/thesis_free_rocking.toml
#     (the reference and every built engine).
# Builds first if needed (scripts/build.sh, incremental). The full grid of every built engine,
# one run at a time, took 10 minutes on a 2-core machine with --repeat 1 (2026-11-23: Housner
# 35 s, free rocking 3.5 min, Rinaldi 228 6 min); the default --repeat 3 (the minimum of three
# wall times, for timing-grade figures) takes about three times that. --quick runs the quick grids
# instead (well under a minute, for checking the pipeline; not for the committed figures).
#
# Usage: scripts/figures.sh [--quick] [--out DIR]      (DIR default: out/figures)
# Environment: ROCKBENCH_BUILD_DIR (default build), ROCKBENCH_SWEEP_ARGS (replaces the timing
# arguments "--threads 1 --repeat 3"), ROCKBENCH_SKIP_BUILD=1 (use the build as it is).
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/figures
quick=()
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=(--quick) ;;
    --out)
      [ $# -ge 2 ] || { echo "figures.sh: --out needs a folder" >&2; exit 2; }
      out=$2
      shift
      ;;
    -h | --help)
      awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"
      exit 0
      ;;
    *)
      echo "figures.sh: unknown argument '$1' (expected --quick or --out DIR)" >&2
      exit 2
      ;;
  esac
  shift
done

build_dir=${ROCKBENCH_BUILD_DIR:-build}
read -r -a sweep_args <<< "${ROCKBENCH_SWEEP_ARGS:---threads 1 --repeat 3}"
if [ "${ROCKBENCH_SKIP_BUILD:-0}" != 1 ]; then
  ROCKBENCH_BUILD_DIR=$build_dir scripts/build.sh
fi
rockbench=$build_dir/src/cli/rockbench
figures=docs/figures
mkdir -p "$figures" "$out"

# Work-precision: sweep, report, copy the two figures of each scene.
for scene in housner_free_rocking thesis_free_rocking thesis_rinaldi228; do
  echo "== sweep of scenes/$scene.toml ($(date -u +%H:%M:%S) UTC)"
  "$rockbench" sweep "scenes/$scene.toml" --out "$out/sweeps/$scene" "${quick[@]}" \
    "${sweep_args[@]}"
  "$rockbench" report "$out/sweeps/$scene" --out "$out/sweep-reports"
  for figure in work_precision peak_error; do
    cp "$out/sweep-reports/$scene/figures/$figure.svg" "$figures/${scene}_$figure.svg"
  done
done

# The run report of the thesis's free-rocking example: the reference and every engine.
echo "== compare of scenes/thesis_free_rocking.toml"
"$rockbench" compare scenes/thesis_free_rocking.toml --out "$out/runs/thesis_free_rocking" \
  --engines all
"$rockbench" report "$out/runs/thesis_free_rocking" --out "$out/run-reports"
for figure in angles angle_error; do
  cp "$out/run-reports/thesis_free_rocking/figures/$figure.svg" \
    "$figures/thesis_free_rocking_compare_$figure.svg"
done

echo "figures in $figures/; reports in $out/sweep-reports/ and $out/run-reports/"
