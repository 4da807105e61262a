#!/usr/bin/env bash
# Quickstart 2: install what is missing, build, and run every test; then build and run the suite
# again with AddressSanitizer and UndefinedBehaviorSanitizer. Exits non-zero if any test fails.
# Usage: tools/test.sh [--no-sanitizers]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
jobs=$(nproc)

bash tools/install-deps.sh

echo "== Release build and tests"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDRAPELAB_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build build -j "$jobs"
ctest --test-dir build -j "$jobs" --output-on-failure

if [[ "${1:-}" != "--no-sanitizers" ]]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDRAPELAB_SANITIZE=ON >/dev/null
  cmake --build build-sanitize -j "$jobs"
  # lsan-suppressions.txt: leaks inside system libraries (Mesa's OSMesa), each explained there.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    LSAN_OPTIONS=suppressions="$root/tools/lsan-suppressions.txt" \
    ctest --test-dir build-sanitize -j "$jobs" --output-on-failure
fi
echo "== all tests passed"
