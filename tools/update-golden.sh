#!/usr/bin/env bash
# The only way the project's golden files change: re-records tests/golden/NAME.json for every
# scenes/NAME.yaml (or the scenes given) from a half-second run, and prints what changed. Review the
# printed changes and `git diff tests/golden` like code before committing them.
# Usage: tools/update-golden.sh [scenes/NAME.yaml ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target drapelab >/dev/null
mkdir -p tests/golden
scenes=("$@")
[[ ${#scenes[@]} -gt 0 ]] || scenes=(scenes/*.yaml)
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  ./build/tools/drapelab/drapelab check "$scene" --golden "tests/golden/$name.json" --update --set duration=0.5
done
