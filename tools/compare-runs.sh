#!/usr/bin/env bash
# Checks that a change leaves behaviour alone: runs scenes with two drapelab binaries (the one
# before the change and the one after) and compares metrics.csv, contacts.csv, compare.csv and
# resolved.yaml byte for byte (none depends on wall-clock time, docs/outputs.md).
# Usage: tools/compare-runs.sh OLD_BINARY NEW_BINARY [DURATION] [SCENE.yaml...]
#   DURATION  seconds simulated per scene (default 0.3); every scene of scenes/ when none is named
#   EXTRA     environment: more `--set key=value` arguments for both runs, e.g.
#             EXTRA="--set solvers.0.integrator=rk4"
# Prints one line per scene ("same", or what differs) and exits 1 if any scene differs.
set -uo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: tools/compare-runs.sh OLD_BINARY NEW_BINARY [DURATION] [SCENE.yaml...]" >&2
  exit 2
fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
old=$(realpath "$1")
new=$(realpath "$2")
duration=${3:-0.3}
shift $(($# < 3 ? $# : 3))
scenes=("$@")
if [[ ${#scenes[@]} -eq 0 ]]; then scenes=("$root"/scenes/*.yaml); fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
differ=0
for scene in "${scenes[@]}"; do
  if [[ ! -f $scene ]]; then
    echo "$scene: no such scene file"
    differ=1
    continue
  fi
  name=$(basename "$scene" .yaml)
  status=""
  for side in old new; do
    binary=$old
    [[ $side == new ]] && binary=$new
    # shellcheck disable=SC2086  # EXTRA holds several arguments
    "$binary" run "$scene" --out "$out/$side/$name" --set "duration=$duration" ${EXTRA:-} -q \
      >/dev/null 2>"$out/$name.$side.err"
    echo $? >"$out/$name.$side.exit"
  done
  cmp -s "$out/$name.old.exit" "$out/$name.new.exit" ||
    status+=" exit $(cat "$out/$name.old.exit") vs $(cat "$out/$name.new.exit");"
  for file in metrics.csv contacts.csv compare.csv resolved.yaml; do
    [[ -f $out/old/$name/$file || -f $out/new/$name/$file ]] || continue
    cmp -s "$out/old/$name/$file" "$out/new/$name/$file" || status+=" $file differs;"
  done
  if [[ -z $status ]]; then
    echo "$name: same"
  else
    echo "$name:$status"
    differ=1
  fi
done
exit $differ
