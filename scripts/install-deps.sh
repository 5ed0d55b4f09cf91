#!/usr/bin/env bash
# Installs the Debian 12 packages Tallow needs to build, test and run. Idempotent: packages that are
# already installed are skipped, and nothing is downloaded when all are present. Uses sudo only when
# not root.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config python3 python3-glad
  # OpenGL contexts: GLFW window, OSMesa (headless default), EGL (Mesa or NVIDIA), llvmpipe driver
  libglfw3-dev libosmesa6-dev libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri libglm-dev
  # scene, images, command line; the view panel's font (units and help: σ, mm⁻¹, →)
  nlohmann-json3-dev libcli11-dev libpng-dev libopenexr-dev libimath-dev libimgui-dev fonts-dejavu-core
  # geometry (libopenvdb-dev's headers need Boost, which it does not pull in)
  libopenvdb-dev libboost-dev libtbb-dev
  # melting meshes on the GPU: NanoVDB (OpenVDB's GPU format, the same 10.0.1 release), whose
  # PNanoVDB.h is compiled as GLSL (embedded into the shaders) and as C over the same grids
  libnanovdb-dev
  # CPU ground truth
  libembree-dev
  # tests: GoogleTest, libFuzzer (clang + its runtime), a virtual display for window tests
  libgtest-dev clang libclang-rt-14-dev xvfb xauth
  # plots of `tallow probe profile` and docs/
  gnuplot-nox
  # `tallow capture --video` and its test (ffprobe reads the video back)
  ffmpeg
  # scripts/device_bundle.sh and its test: strip/objdump (binutils), the archive (tar, xz), `timeout`
  binutils xz-utils tar coreutils
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
