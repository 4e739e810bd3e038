#!/usr/bin/env bash
# Sets up and runs the default scene: installs the Debian packages, builds, and simulates the
# built-in hanging cloth, exporting every 30th frame to out/default/ and statistics to
# out/default/stats.json. Extra arguments go to `glcollide run`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build_dir=${GLCOLLIDE_BUILD_DIR:-build}
mkdir -p out/default
"$build_dir"/src/glcollide run --export out/default --every 30 --stats out/default/stats.json "$@"
