#!/usr/bin/env bash
# Installs the Debian 12 packages drapelab needs, only those missing. Uses sudo when not root.
# Usage: tools/install-deps.sh [--print]   (--print lists the packages and exits)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config   # compiler and build tools
  libeigen3-dev                                  # vectors and matrices (engine)
  libfcl-dev                                     # exact particle-collider contact (engine)
  libgmp-dev                                     # exact orient3d for the self-intersection audit (engine)
  libbullet-dev                                  # Bullet 3.24, double build bullet-float64 (bullet_bridge)
  libmujoco-dev                                  # MuJoCo 2.2.2, the third engine (mujoco_bridge)
  libyaml-cpp-dev                                # scene files
  libcli11-dev                                   # command line
  nlohmann-json3-dev                             # summary.json
  libosmesa6-dev libgl-dev                       # drapelab render: offscreen OpenGL (Mesa; no display or GPU)
  libfreetype-dev fonts-dejavu-core              # drapelab render: label text and its font
  ffmpeg                                         # drapelab render: render/video.mp4 from the frames
  libglfw3-dev libimgui-dev                      # drapelab view: its window and input, its controls
  xvfb                                           # tests: drapelab view in a virtual display
  python3-dev pybind11-dev python3-numpy         # the Python module (import drapelab)
  python3-pytest python3-matplotlib              # its tests; the sweep-plotting example
  slurmctld slurmd slurm-client munge            # tests: sweeps on a one-node Slurm (tools/slurm-local.sh)
  libgtest-dev libgmock-dev                      # tests
  libxml2-dev libpng-dev                         # tests (HTML report, screenshot); PNG files of drapelab render
  chromium                                       # tests: open the HTML report headless
  libbenchmark-dev                               # micro-benchmarks (bench/)
  clang-format                                   # the format check of tools/test.sh (.clang-format)
  clang libclang-rt-dev libomp-dev               # tests: the clang sanitizer build and its fuzz targets
)

if [[ "${1:-}" == "--print" ]]; then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: every package is already installed"
  exit 0
fi

as_root=()
if [[ $(id -u) -ne 0 ]]; then
  if ! command -v sudo >/dev/null; then
    echo "install-deps: missing ${missing[*]}; run this script as root or install sudo" >&2
    exit 1
  fi
  as_root=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
