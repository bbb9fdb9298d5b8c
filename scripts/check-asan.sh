#!/bin/sh
# The whole test suite under AddressSanitizer, LeakSanitizer and UBSan
# (./configure --enable-asan: undefined behaviour stops the program, leaks
# fail the test) in BUILD_DIR (default build-asan beside configure.ac).
# About 20 minutes of wall time on 2 cores shared with other work (the Monte
# Carlo tests run 2-3 times slower under ASan).
#   sh scripts/check-asan.sh [BUILD_DIR] [MORE_CONFIGURE_OPTIONS...]
src=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$src/build-asan}
[ $# -gt 0 ] && shift
exec sh "$src/scripts/check-build.sh" "$dir" --enable-asan "$@"
