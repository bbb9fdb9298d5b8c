#!/bin/sh
# The long kill sweep of issue 23: every writer killed at every rename,
# renameat2, unlink, rmdir, mkdir, fsync, write and pwrite64 of a run
# (tests/outdir_kill_writers.sh with both steps 1), first with the atomic
# exchange, then with renameat2 failing (the two-step fallback).  Run from
# a configured build directory: sh scripts/kill-sweep.sh [WRITER...].
# About 15 minutes on 2 cores.
top=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$PWD}
[ -x "$build/skinbake" ] || { echo "kill-sweep.sh: no $build/skinbake (run it from the build directory)" >&2; exit 2; }
[ $# -gt 0 ] && KILL_WRITERS="$*" && export KILL_WRITERS
rc=0
for ex in yes no; do
	echo "# exchange: $ex"
	KILL_STEP=1 KILL_STEP_RARE=1 KILL_EXCHANGE=$ex SKINBAKE="$build/skinbake" top_srcdir="$top" \
		sh "$top/tests/outdir_kill_writers.sh" || rc=1
done
exit $rc
