#!/usr/bin/env bash
# The only way the project's golden files change: re-records tests/golden/NAME.json for every
# scenes/NAME.yaml (or the scenes given) and prints what changed. Review the printed changes and
# `git diff tests/golden` like code before committing them.
# Each recording is three runs: the scene, and two probe runs with gravity changed by +-1e-10 of
# itself that measure how far rounding moves each quantity (docs/contact.md, "Golden files").
# Usage: tools/update-golden.sh [scenes/NAME.yaml ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
# Builds share one lock with everyone working in this checkout.
flock /tmp/drapelab-build.lock sh -c \
  'cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null && cmake --build build --target drapelab >/dev/null'
mkdir -p tests/golden

# The run each golden file records: half a second, long enough for every cloth to reach its
# colliders, except where a contact parameter acts only later:
#   incline_slide  the cloth lies on the board from frame 0 and slides at a steady rate, where the
#                  contact damping does nothing; it acts when the cloth leaves the board (about
#                  1.1 s) and lands on the floor, so the file records the scene's whole 2 s.
#   window_curtain the breeze first draws the curtain back onto the window frame at about 1.3 s:
#                  the file records 2 s.
#   parachute      the descent reaches its steady speed after about a second: the file records
#                  the whole 2.5 s.
#   mannequin_tshirt the shirt is sewn over its first 0.15 s and settles onto the shoulders by
#                  1 s, where the contact carries it: the file records 1 s.
#   free_fall      its explicit Euler solver gains energy and becomes unstable at 0.25 s, and
#                  --update records only runs whose every solver is ok: the file records 0.2 s.
duration_of() {
  case "$1" in
    incline_slide) echo 2.0 ;;
    window_curtain) echo 2.0 ;;
    parachute) echo 2.5 ;;
    free_fall) echo 0.2 ;;
    mannequin_tshirt) echo 1.0 ;;
    *) echo 0.5 ;;
  esac
}

# The solvers each golden file records: all of the scene's, except where one costs too much for a
# test of a minute of CPU:
#   mannequin_tshirt Bullet's deformable cloth takes about 870 wall s per simulated s on the
#                  mannequin (its explicit step of 63 us, face contacts on 13,360 triangles): the
#                  file records ours alone.
solvers_of() {
  case "$1" in
    mannequin_tshirt) echo '--set=solvers=[{name: ours, type: spring_damper, integrator: vbd}]' ;;
    *) echo '' ;;
  esac
}
scenes=("$@")
[[ ${#scenes[@]} -gt 0 ]] || scenes=(scenes/*.yaml)
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  solvers=$(solvers_of "$name")
  ./build/tools/drapelab/drapelab check "$scene" --golden "tests/golden/$name.json" --update \
    --set "duration=$(duration_of "$name")" ${solvers:+"$solvers"}
done
