#!/usr/bin/env bash
# Installs what a fresh Debian 12 machine lacks to build and test glcollide, Mesa's EGL and
# llvmpipe included (the GL tests run on it when there is no GPU), and clang with its sanitizer and
# libFuzzer runtimes plus llvm-symbolizer (scripts/test-sanitizers.sh), and clang-format
# (scripts/format.sh --check), and ffmpeg (`glcollide render --video`, tests/cli/render_video_test.sh), and
# GLFW, Dear ImGui (with its GLFW and OpenGL 3 backends), Xvfb and xauth for `glcollide view` and its
# tests under xvfb-run (tests/cli/view_test.sh). Needs root (or sudo).
set -euo pipefail
packages=(
  build-essential cmake pkg-config git python3
  libepoxy-dev libegl-dev libglm-dev nlohmann-json3-dev libcli11-dev libassimp-dev
  libgtest-dev libgmock-dev glslang-tools libgmp-dev libstb-dev
  libegl1 libegl-mesa0 libgl1-mesa-dri libgl1 libopengl0
  clang libclang-rt-14-dev llvm clang-format
  ffmpeg
  libglfw3-dev libimgui-dev xvfb xauth
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
