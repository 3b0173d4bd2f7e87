#!/usr/bin/env bash
# Set up (packages + build) and run the whole test suite with CTest.
#   tools/test.sh [ctest args...]    e.g. tools/test.sh -L unit
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/tools/setup.sh"
ctest --test-dir "$here/build" --output-on-failure -j "$(nproc)" "$@"
