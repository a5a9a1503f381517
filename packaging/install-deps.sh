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

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
  SUDO="sudo"
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
