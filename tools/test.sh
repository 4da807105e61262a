#!/usr/bin/env bash
# Quickstart 2: install what is missing, check the format, build, and run every test but the `slow`
# label; then build and run the `fast` and `physics` labels again with AddressSanitizer and
# UndefinedBehaviorSanitizer, and fuzz the scene loader and the OBJ reader for a fixed number of
# inputs (clang's libFuzzer). Exits non-zero if the format check, any test or a fuzz run fails.
# Usage: tools/test.sh [--fast | --all | --no-sanitizers]
#   --fast           build, then run only the `fast` label (tests/CMakeLists.txt); no sanitizer build
#   --all            the `slow` label too: the full-size runs whose CI-sized twins the default runs
#   --no-sanitizers  every test but the `slow` label, without the sanitizer and fuzz builds
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
jobs=$(nproc)
mode=${1:-}
case "$mode" in
  "" | --fast | --all | --no-sanitizers) ;;
  *) echo "usage: tools/test.sh [--fast | --all | --no-sanitizers]" >&2; exit 2 ;;
esac

bash tools/install-deps.sh

echo "== Format check (.clang-format)"
# Every tracked C++ file as clang-format writes it; `clang-format -i FILE` fixes one that is not.
git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run --Werror

# Unity builds take about half the CPU time of a whole build (CMakeLists.txt,
# DRAPELAB_UNITY_BUILD): on in a new tree; a tree that chose already keeps its choice (a developer's
# -DDRAPELAB_UNITY_BUILD=OFF, for quicker rebuilds after an edit).
unity_option() {
  grep -qs '^DRAPELAB_UNITY_BUILD:' "$1/CMakeCache.txt" || echo -DDRAPELAB_UNITY_BUILD=ON
}

echo "== Release build and tests${mode:+ ($mode)}"
# DRAPELAB_BUILD_TESTS=ON: tools/demo.sh configures the same tree without the tests.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDRAPELAB_WARNINGS_AS_ERRORS=ON \
  -DDRAPELAB_BUILD_TESTS=ON $(unity_option build) >/dev/null
cmake --build build -j "$jobs"
if [[ "$mode" == "--fast" ]]; then
  ctest --test-dir build -j "$jobs" -L fast --no-tests=error --output-on-failure
  echo "== fast tests passed"
  exit 0
fi
# The `slow` label holds the full-size runs (over a minute of CPU each); each has a CI-sized twin
# in the default run (tests/CMakeLists.txt lists them). --all runs them too.
not_slow=(-LE slow)
[[ "$mode" == "--all" ]] && not_slow=()
ctest --test-dir build -j "$jobs" "${not_slow[@]}" --no-tests=error --output-on-failure

if [[ "$mode" != "--no-sanitizers" ]]; then
  # lsan-suppressions.txt: leaks inside system libraries (Mesa's OSMesa), each explained there.
  sanitizer_env=(env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
                 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
                 LSAN_OPTIONS=suppressions="$root/tools/lsan-suppressions.txt")

  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build (clang): fast, physics and fuzz tests"
  # One clang tree for the sanitizer run and the libFuzzer targets (tests/fuzz/CMakeLists.txt): each
  # fuzzer runs a fixed number of inputs from a fixed seed. -gline-tables-only: the line tables the
  # sanitizers' stack traces need, at a fraction of full debug info's build time.
  # -Wno-pass-failed: clang reports every `omp simd` loop it leaves scalar at -O2.
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER=clang++ -DDRAPELAB_SANITIZE=ON -DDRAPELAB_FUZZ=ON $(unity_option build-sanitize) \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG -Wno-pass-failed" >/dev/null
  cmake --build build-sanitize -j "$jobs" --target tests_fast_physics fuzzers
  # A few long runs go in the Release build only, each one whose code paths other cases of the
  # same suite take under the sanitizers too (CI has 30 minutes; these took 10 CPU minutes there):
  # the stacked sheets (the other self-collision cases), the V10 drape runs and V9's sticking
  # threshold, and the continuum sheet settled under every integrator (the
  # continuum's forces run under them in test_continuum_elements and the suite's other cases, every
  # integrator's step in the spring suites).
  skipped='StackedSheetsRestOneThicknessApartAndNeverCross|RaisingBendStiffnessNeverLowersTheDrapeCoefficient'
  skipped+='|TheSameSeedReproducesTheDrapeCoefficient|AVeryStiffClothStaysNearlyFlat'
  skipped+='|V9StickingThresholdIsTheFrictionAngle|EveryIntegratorSettlesToTheSameHangingShape'
  # The sharp-edge energy runs at small explicit steps: symplectic Euler's case keeps the bounded
  # edge contacts under the sanitizers (and ExplicitContactBound in the fast label the bound itself).
  skipped+='|SharpEdgeEnergy[.]Defaults|EveryExplicitIntegrator[.].*(explicit_euler|midpoint|rk4|verlet|leapfrog)'
  # The twisted strip's twin (20 s of CPU in Release) and the throw at 20 m/s (63 s under the
  # sanitizers): the crumple runs vbd's offset contacts, their detections, bounds and barrier,
  # under the sanitizers.
  skipped+='|IntersectionFreeCi[.]TheTwistedStripNeverCrossesItself'
  skipped+='|IntersectionFree[.]ASheetThrownAt20MetresPerSecondOntoAnotherLandsOnIt'
  # vbd at sharp edges (47 s of CPU for the two box runs there) in Release only; the crumple
  # between two box plates keeps vbd's feature and offset contacts under the sanitizers.
  skipped+='|SharpEdgeEnergy[.]Vbd(AtItsDefaultStepGainsNoEnergyOnABoxEdge|WithAHeavierSheet)'
  # Over a minute of CPU each under the sanitizers, so Release only: the energy ledger of every
  # integrator (their steps run under the sanitizers in the attachment and spring suites), V9's
  # slide (the friction paths run in the sharp-edge and cylinder-cap cases), the V8 sphere drapes
  # (vbd's stiff sheet on a sphere keeps the sphere contact, test_adaptive_substeps the adaptive
  # substeps), V10's limp cloth (the Cusick specimen runs in AutomaticIntegrator's
  # case, the drape metric in the fast label), the face-on sheet's terminal speed (the hinged plate
  # keeps the air's forces) and the continuum's large steps on a stiff fabric (its integrators run
  # in the suite's other cases).
  skipped+='|EveryIntegratorBalancesASwingingDampedSheet|V9SlidesWithTheCoulombAccelerationOnASteep'
  skipped+='|V8ClothDrapedOnASphereRests|V8ClothDroppedOnASphereRests|ALimpHeavyClothHangsDown'
  skipped+='|V8DrapeHoldsWithAdaptiveSubsteps|Air[.]AFaceOnSheetReachesItsTerminalSpeed'
  skipped+='|LargeStepSchemesStayStableOnAStiffFabricAtASixtiethOfASecond'
  # The sphere drape on a mesh (24 s of CPU under the sanitizers): the mesh's queries run there in
  # test_contact's MeshSurface cases, its loading in test_scenes' MeshColliderScene cases.
  skipped+='|MeshDrape[.]ASphereGivenAsAMeshDrapesLikeTheSphere'
  "${sanitizer_env[@]}" ctest --test-dir build-sanitize -j "$jobs" -L 'fast|physics|fuzz' \
    -LE slow -E "$skipped" --no-tests=error --output-on-failure
fi
echo "== all tests passed"
