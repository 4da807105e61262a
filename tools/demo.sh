#!/usr/bin/env bash
# Quickstart 1: install what is missing, build in Release, run the default scene, list the outputs.
# Usage: tools/demo.sh [SCENE] [OUT_DIR]   (default: scenes/sphere_drape.yaml into out/sphere_drape)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scene=${1:-scenes/sphere_drape.yaml}
out=${2:-out/$(basename "$scene" .yaml)}

bash tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDRAPELAB_BUILD_TESTS=OFF >/dev/null
cmake --build build --target drapelab
./build/tools/drapelab/drapelab run "$scene" --out "$out" --force
echo
echo "drapelab is at build/tools/drapelab/drapelab; the run is in $out/ (see README.md, 'What a run writes')."
