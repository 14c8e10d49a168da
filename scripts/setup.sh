#!/usr/bin/env bash
# Installs the Debian packages viqu needs (only those missing), then configures and builds
# into ./build (Release). Safe to run repeatedly. Needs root (or sudo) only when something is missing.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

# libqhull-dev: Debian's MuJoCo CMake config lists /usr/include/libqhull_r among its include dirs.
# libglfw3-dev: the optional viewer (viqu view); xvfb, xdotool: its tests open the window on a
# virtual display and press its keys. clang, libclang-rt-14-dev: the libFuzzer targets (CI's sanitizer
# stage, scripts/sanitize.sh ci).
packages=(
  build-essential cmake pkg-config ccache
  libmujoco-dev libqhull-dev libeigen3-dev libopencv-dev liburdfdom-dev libconsole-bridge-dev zlib1g-dev libceres-dev libyaml-cpp-dev
  libegl-dev libopengl-dev libgl1-mesa-dri libegl-mesa0
  googletest libgtest-dev libbenchmark-dev
  python3-matplotlib python3-numpy python3-yaml
  libglfw3-dev xvfb xdotool
  clang libclang-rt-14-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "viqu setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs=${VIQU_JOBS:-$(nproc)}
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j"$jobs"
