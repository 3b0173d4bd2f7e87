#!/usr/bin/env bash
# Builds the reader fuzzers with Clang (libFuzzer + ASan + UBSan) in their own build folder, seeds
# them from tests/data (make_fuzz_seeds) and runs each in turn.
#   tools/fuzz/run.sh [--build-dir DIR] [--seconds N] [--corpus DIR] [--targets "tilt json ..."]
#                     [-- libFuzzer options]
# Defaults: build-fuzz/, 60 s per target, corpora kept in DIR/corpus/<target>, every target.
# Crashes, leaks, timeouts (10 s per input) and inputs over 1024 MB of memory end the run with
# status 1; the input is saved in DIR/artifacts/<target>/. Exit status 77 (skipped) when clang++-14
# or its libFuzzer runtime (Debian libclang-rt-14-dev) is missing.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$here/build-fuzz"
seconds=60
corpus=""
targets="tilt tilt_dir curves obj json mesh_obj mesh_ply"
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build="$2"; shift ;;
    --seconds) seconds="$2"; shift ;;
    --corpus) corpus="$2"; shift ;;
    --targets) targets="$2"; shift ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "fuzz/run.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done
corpus="${corpus:-$build/corpus}"

if ! command -v clang++-14 >/dev/null; then
  echo "fuzz: skipped: clang++-14 is not installed (Debian package clang-14)" >&2
  exit 77
fi
runtime="$(clang++-14 -print-resource-dir)/lib/linux/libclang_rt.fuzzer-x86_64.a"
if [ ! -f "$runtime" ]; then
  echo "fuzz: skipped: no libFuzzer runtime at $runtime (Debian package libclang-rt-14-dev)" >&2
  exit 77
fi

CC=clang-14 CXX=clang++-14 cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSKETCHSURF_FUZZ=ON -DSKETCHSURF_ENGINE=OFF -DSKETCHSURF_TESTS=OFF -DSKETCHSURF_BENCHMARKS=OFF \
  >/dev/null
fuzzers=()
for t in $targets; do fuzzers+=("fuzz_$t"); done
cmake --build "$build" --target make_fuzz_seeds "${fuzzers[@]}" -j "$(nproc)"
rm -rf "$build/seeds"
"$build/tools/fuzz/make_fuzz_seeds" "$here/tests/data" "$build/seeds"

# Each input is written to a file before it is read: in memory when /dev/shm is there.
[ -w /dev/shm ] && export TMPDIR=/dev/shm
# Leaks are reported when the process exits; a reader that only returns early never frees late.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
for t in $targets; do
  mkdir -p "$corpus/$t" "$build/artifacts/$t"
  log="$build/artifacts/$t/last_run.log"
  if "$build/tools/fuzz/fuzz_$t" -max_total_time="$seconds" -rss_limit_mb=1024 -timeout=10 \
       -print_final_stats=1 -artifact_prefix="$build/artifacts/$t/" "${extra[@]}" \
       "$corpus/$t" "$build/seeds/$t" >"$log" 2>&1; then
    result=ok
  else
    result=FAILED
    status=1
    grep -E "ERROR|SUMMARY|reader_fuzzer:|Test unit written" "$log" | head -20 >&2 || true
  fi
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
  echo "fuzz_$t: $result, ${execs:-?} runs in ${seconds} s, corpus $(ls "$corpus/$t" | wc -l) files" \
       "($(du -sk "$corpus/$t" | cut -f1) KiB), log $log"
done
exit "$status"
