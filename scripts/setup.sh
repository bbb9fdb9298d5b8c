#!/bin/sh
# One-step set-up on Debian 12 or 13: install every package skinbake builds, tests
# and renders with (apt-get, as root or through sudo), create the Python test
# environments (.venv/, .venv-bpy45/) from the pinned requirements files, then
# configure and build.  Idempotent; extra arguments go to ./configure.
set -eu
cd "$(dirname "$0")/.."
start=$(date +%s)
PKGS="build-essential autoconf automake pkg-config autoconf-archive \
 libopenexr-dev openexr libpng-dev libjson-c-dev libinih-dev libqhull-dev \
 librandom123-dev libcmocka-dev libassimp-dev assimp-testmodels libopenmpi-dev openmpi-bin libopenblas-dev liblapacke-dev \
 gnuplot-nox hyperfine python3 python3-venv povray blender strace clang libssl-dev"
SUDO=
if [ "$(id -u)" != 0 ]; then
	if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
		echo "setup.sh: run as root or install sudo (apt-get needs root)" >&2; exit 1; fi
fi
apt_update() {
	$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -q
	updated=1
}
updated=
# A fresh machine has no package lists: apt-cache knows nothing until the first update.
apt-cache show build-essential >/dev/null 2>&1 || apt_update
have() { apt-cache show "$1" >/dev/null 2>&1; }
# first of the named packages that apt offers (names differ between Debian releases)
pick() {
	for p in "$@"; do
		if have "$p"; then echo "$p"; return 0; fi
	done
	echo "setup.sh: none of $* is offered by apt (Debian $(cat /etc/debian_version))" >&2
	return 1
}
# The sanitizers' runtime must match clang's major version: clang 14 on Debian 12, 19 on 13.
clangv=$(apt-cache depends clang 2>/dev/null | sed -n 's/^ *Depends: clang-\([0-9][0-9]*\)$/\1/p' | head -n 1)
[ -n "$clangv" ] || { echo "setup.sh: apt does not say which clang-NN the clang package is" >&2; exit 1; }
PKGS="$PKGS $(pick "libclang-rt-$clangv-dev")"
# bpy (Blender as a Python module, in the venvs) loads X11 and GL libraries that Debian's blender
# package does not pull in without recommends (libXt has its t64 name on 13), and bpy 5.x aborts
# in a render without EGL (Mesa's llvmpipe when headless).
PKGS="$PKGS libsm6 libice6 libopengl0 $(pick libxt6t64 libxt6) libegl1 libegl-mesa0 libgl1-mesa-dri"
# Mitsuba's LLVM variants (drjit 1.5) need libLLVM >= 16: Debian 12's default 14 crashes them.
# (Debian 13 renamed some for 64-bit time: libllvm17t64.)
PKGS="$PKGS $(pick libllvm19 libllvm20 libllvm18 libllvm18t64 libllvm17 libllvm17t64 libllvm16)"
missing=
for p in $PKGS; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
	echo "setup.sh: installing$missing"
	[ -n "$updated" ] || apt_update
	# shellcheck disable=SC2086
	$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $missing
fi
sh scripts/setup-venv.sh
if [ ! -f configure ] || [ configure.ac -nt configure ]; then autoreconf -fi; fi
if [ ! -f Makefile ] || [ configure -nt Makefile ]; then ./configure --with-mpi "$@"; fi
make -j"$(nproc)"
# Which Blenders the tests run on here: Debian's package and each bpy venv (tests/blender_matrix.sh).
ver() { sed 's/^[0-9]*://; s/[+~-].*//'; }
bpyv() { "$1/bin/python" -c 'import importlib.metadata as m; print(m.version("bpy"))' 2>/dev/null || echo none; }
tested="Debian's blender $(dpkg-query -W -f='${Version}' blender | ver), bpy $(bpyv .venv) (.venv)"
if [ -x .venv-bpy45/bin/python ]; then tested="$tested, bpy $(bpyv .venv-bpy45) (.venv-bpy45)"; else
	tested="$tested; not bpy 4.5 LTS (wheels for Python 3.11 only)"; fi
if [ -x .venv-bpy43/bin/python ]; then tested="$tested, bpy $(bpyv .venv-bpy43) (.venv-bpy43)"; fi
echo "setup.sh: Debian $(cat /etc/debian_version), Python $(/usr/bin/python3 -c 'import platform; print(platform.python_version())')," \
	"gcc $(gcc -dumpfullversion), clang $clangv; Blender tested here: $tested"
echo "setup.sh: done in $(( $(date +%s) - start )) s"
