#!/bin/sh
# Configure, build and run the whole test suite in a build directory of
# its own, so that the normal build is left alone: the sanitizer build
# (scripts/check-asan.sh), the fuzzing build, --disable-openmp, --without-mpi.
#
#   sh scripts/check-build.sh BUILD_DIR [CONFIGURE_OPTION...]
#
# CHECK_TARGET=check-fast runs the fast tier instead (scripts/check-debug.sh).
#
# Prints the failing tests, the closing "N passed, N failed, N skipped" line
# and the wall time; exit status 0 only when every test passed.
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
[ $# -ge 1 ] || { echo "usage: check-build.sh BUILD_DIR [CONFIGURE_OPTION...]" >&2; exit 2; }
build=$1
shift
t0=$(date +%s)
mkdir -p "$build" || exit 1
build=$(cd "$build" && pwd)
if [ -f "$src/config.status" ]; then
	# The source tree is configured in place (scripts/setup.sh does that),
	# and autoconf builds elsewhere only from a clean tree: build a copy of
	# the checked-out files (with uncommitted changes) instead.
	if ! (cd "$src" && git rev-parse --is-inside-work-tree) >/dev/null 2>&1; then
		echo "check-build: $src is configured in place and is not a git checkout; run make distclean there" >&2
		exit 1
	fi
	rm -rf "$build/src"
	mkdir -p "$build/src"
	(cd "$src" && git ls-files -z | xargs -0 tar -cf - 2>/dev/null) | (cd "$build/src" && tar -xf -) || exit 1
	(cd "$build/src" && autoreconf -fi >/dev/null 2>&1) || { echo "check-build: autoreconf failed" >&2; exit 1; }
	top=$build/src
	build=$build/b
	mkdir -p "$build"
else
	top=$src
	[ -f "$top/configure" ] || (cd "$top" && autoreconf -fi) || exit 1
fi
cd "$build" || exit 1
if ! "$top/configure" -q "$@" >configure.out 2>&1; then
	tail -20 configure.out
	echo "0 passed, 1 failed"
	exit 1
fi
# UBSan reports with stack traces.  (LeakSanitizer is on by default; an
# ASAN_OPTIONS here would override skinbake-mpi's own, which turns it off.)
UBSAN_OPTIONS="${UBSAN_OPTIONS:+$UBSAN_OPTIONS:}print_stacktrace=1"
export UBSAN_OPTIONS
make -j"${JOBS:-2}" >make.out 2>&1 || { tail -30 make.out; echo "0 passed, 1 failed"; exit 1; }
make -j"${JOBS:-2}" "${CHECK_TARGET:-check}" >check.out 2>&1
rc=$?
grep -E '^(FAIL|ERROR|XPASS):' check.out
sh "$top/scripts/test-summary.sh" test-suite.log
echo "check-build $*: $(( $(date +%s) - t0 )) s in $build"
exit $rc
