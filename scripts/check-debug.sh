#!/bin/sh
# The debug build's fast tier: configure --enable-debug (DCHECK in
# src/base/check.h: photon weights, unit direction cosines and the energy
# of every photon booked, checked in the transport kernel) in a build
# directory of its own and run `make check-fast` there.  .ci/debug runs it.
#
#   sh scripts/check-debug.sh [BUILD_DIR] [CONFIGURE_OPTION...]   (default build-debug)
set -u
dir=${1:-build-debug}
[ $# -ge 1 ] && shift
CHECK_TARGET=check-fast exec sh "$(dirname "$0")/check-build.sh" "$dir" --enable-debug "$@"
