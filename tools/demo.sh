#!/usr/bin/env bash
# Quickstart 1: install what is missing, build in Release, run the default scene, list the outputs,
# render its frames and render/video.mp4 (ffmpeg) and write its HTML report, whose path comes last.
# Usage: tools/demo.sh [SCENE] [OUT_DIR]   (default: scenes/sphere_drape.yaml into out/sphere_drape)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scene=${1:-scenes/sphere_drape.yaml}
out=${2:-out/$(basename "$scene" .yaml)}

bash tools/install-deps.sh
# A unity build in a new tree (about half the CPU time; CMakeLists.txt, DRAPELAB_UNITY_BUILD); a tree
# that chose already keeps its choice.
unity=-DDRAPELAB_UNITY_BUILD=ON
grep -qs '^DRAPELAB_UNITY_BUILD:' build/CMakeCache.txt && unity=
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDRAPELAB_BUILD_TESTS=OFF $unity >/dev/null
cmake --build build --target drapelab
drapelab=./build/tools/drapelab/drapelab
# Render only when this build has the render verb (asked at run time); it draws from the run's
# point caches, so the run then also writes meshes/.
render=no
meshes=()
if "$drapelab" render --help >/dev/null 2>&1; then
  render=yes
  meshes=(--meshes pc2)
fi
"$drapelab" run "$scene" --out "$out" --force "${meshes[@]}"
if [[ $render == yes ]]; then
  # A failed render (no OpenGL, say) leaves the report without pictures, not without a report.
  "$drapelab" render "$out" || echo "demo: drapelab render failed; the report will say how to render later" >&2
fi
report=$("$drapelab" report "$out")
echo
echo "drapelab is at build/tools/drapelab/drapelab; the run is in $out/ (see README.md, 'What a run writes')."
if [[ -f $out/render/video.mp4 ]]; then
  echo "video: $out/render/video.mp4"
fi
echo "report: $report"
