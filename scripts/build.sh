#!/usr/bin/env bash
# Configures and builds glcollide into ./build (or $GLCOLLIDE_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${GLCOLLIDE_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${GLCOLLIDE_CMAKE_ARGS:-}
cmake --build "$build_dir" -j "$(nproc)"
