#!/bin/sh
# One-step set-up on Debian 12: install every package skinbake builds, tests
# and renders with (apt-get, as root or through sudo), then configure and
# build.  Idempotent; extra arguments go to ./configure.
set -eu
cd "$(dirname "$0")/.."
PKGS="build-essential autoconf automake pkg-config autoconf-archive \
 libopenexr-dev openexr libpng-dev libjson-c-dev libinih-dev libqhull-dev \
 librandom123-dev libcmocka-dev libassimp-dev assimp-testmodels libopenmpi-dev openmpi-bin libopenblas-dev liblapacke-dev \
 gnuplot-nox hyperfine python3 povray blender strace clang libclang-rt-14-dev libssl-dev"
SUDO=
if [ "$(id -u)" != 0 ]; then
	if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
		echo "setup.sh: run as root or install sudo (apt-get needs root)" >&2; exit 1; fi
fi
missing=
for p in $PKGS; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
	echo "setup.sh: installing$missing"
	$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -q
	# shellcheck disable=SC2086
	$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $missing
fi
if [ ! -f configure ] || [ configure.ac -nt configure ]; then autoreconf -fi; fi
if [ ! -f Makefile ] || [ configure -nt Makefile ]; then ./configure --with-mpi "$@"; fi
make -j"$(nproc)"
