#!/usr/bin/env bash
# Installs every build, test and benchmark dependency of MotionStyle from Debian 12 packages.
# Idempotent and non-interactive; run as root (or through sudo) on a fresh Debian 12 machine.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git ca-certificates
  # clang: libFuzzer target and sanitizer runtime
  clang libclang-rt-14-dev
  # core libraries
  libeigen3-dev libceres-dev nlohmann-json3-dev
  # desktop app: Qt6 widgets + Qt6 OpenGL, VTK 9 (rendering only, into a Qt6 OpenGL framebuffer object)
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev libgl-dev libvtk9-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth libgl1-mesa-dri xdotool
  # packaging
  dpkg-dev file
  # the CLI mutation test (tests/cli/mutation_test.py)
  python3
)
# Wanted but not required: a test that needs one skips with a message when it is absent.
optional=(
  # Blender 3.4, the user's other tool in tests/blender (reads and writes BVH headless)
  blender
)

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
missing=()
for p in "${packages[@]}"; do installed "$p" || missing+=("$p"); done
missing_optional=()
for p in "${optional[@]}"; do installed "$p" || missing_optional+=("$p"); done

if [ ${#missing[@]} -eq 0 ] && [ ${#missing_optional[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages (and ${#optional[@]} optional) already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
  SUDO="sudo"
fi

export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [ ${#missing_optional[@]} -gt 0 ]; then
  echo "install-deps: installing (optional) ${missing_optional[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${missing_optional[@]}" >/dev/null ||
    echo "install-deps: could not install ${missing_optional[*]}: the tests that need them will skip"
fi
echo "install-deps: done"
