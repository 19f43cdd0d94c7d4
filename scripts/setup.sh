#!/usr/bin/env bash
# Command 1: installs the Debian packages, builds in Release, compares the engines with the
# reference model on the default scene (the thesis's free-rocking example), writes its report,
# and prints the report's path and one verdict per engine.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
run=out/thesis_free_rocking
mkdir -p out
./build/src/cli/rockbench compare scenes/thesis_free_rocking.toml --out "$run" | tee "$run.log.tmp"
./build/src/cli/rockbench report "$run" --out out/report >/dev/null
mv "$run.log.tmp" "$run/compare.log"
echo
echo "report: $PWD/out/report/$(basename "$run")/report.html"
grep '^verdict ' "$run/compare.log"
