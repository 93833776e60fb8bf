#!/usr/bin/env bash
# The test command of the README and of CI: installs what is missing, builds, runs every test.
# FISSURE_TEST_LABEL=unit (or slow, bench-smoke, gui) runs one label only.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/install-deps.sh" --gui
"$root/scripts/build.sh"
build_dir=${FISSURE_BUILD_DIR:-$root/build}
label_args=()
if [[ -n "${FISSURE_TEST_LABEL:-}" ]]; then label_args=(-L "$FISSURE_TEST_LABEL"); fi
cd "$build_dir"
ctest --output-on-failure --parallel "${FISSURE_JOBS:-$(nproc)}" "${label_args[@]}"
