#!/usr/bin/env bash
# Builds the sketch-model and sketch-format tests with AddressSanitizer + UBSan (in build-asan) and
# runs them: the sketch model, .tilt (including every truncation and the random corruptions) and
# .json, plus the .tilt reader on the real sketches when they are present.
#   tools/sanitize.sh [extra ctest args...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$here/build-asan"

cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSKETCHSURF_SANITIZE=ON -DSKETCHSURF_ENGINE=OFF -DSKETCHSURF_BENCHMARKS=OFF
targets=(sketch_unit_tests tilt_tests tilt_robustness_tests sketch_format_tests)
if [[ -e "$build/tests/unit/sketch/CTestTestfile.cmake" ]] &&
   grep -q tilt_data_tests "$build/tests/unit/sketch/CTestTestfile.cmake"; then
  targets+=(tilt_data_tests)
fi
cmake --build "$build" --target "${targets[@]}" -j "$(nproc)"

# Any sanitizer report fails the test that triggered it.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "$build" -L 'unit|data' -R '^(Sketch|Clean|Resample|Tilt|Json)' \
  --output-on-failure -j "$(nproc)" "$@"
