#!/usr/bin/env bash
# Command 1: installs the Debian packages, builds in Release and runs the default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
./build/src/cli/rockbench run scenes/thesis_free_rocking.toml --out out/thesis_free_rocking
