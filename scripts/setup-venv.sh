#!/bin/sh
# The Python test environments, made by scripts/setup.sh (and only there: nothing is
# downloaded when skinbake or its tests run).
#   .venv/        requirements-test.txt: bpy (the newest release with wheels for this
#                 machine's Python), numpy, scipy, mitsuba, drjit
#   .venv-bpy45/  requirements-bpy45.txt: bpy 4.5 LTS, which has wheels for Python 3.11
#                 only (Debian 12); on another Python it is skipped with a line saying so
#   .venv-bpy43/  requirements-bpy43.txt: bpy 4.3 (Debian 13's Blender line), Python 3.11 only too
# Debian's own python3 is used, not one on the PATH (pyenv and the like differ per machine).
# A venv is made again when its requirements file changed.
set -eu
cd "$(dirname "$0")/.."
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
pyv=$("$PY" -c 'import sys; print("%d.%d" % sys.version_info[:2])')

mkvenv() {      # DIR REQUIREMENTS
	if [ -x "$1/bin/python" ] && cmp -s "$2" "$1/requirements.installed"; then
		echo "setup-venv.sh: $1 is up to date ($2)"
		return 0
	fi
	echo "setup-venv.sh: creating $1 from $2 (Python $pyv)"
	rm -rf "$1"
	"$PY" -m venv "$1"
	"$1/bin/python" -m pip install -q --disable-pip-version-check -r "$2"
	cp "$2" "$1/requirements.installed"
}
mkvenv .venv requirements-test.txt
if [ "$pyv" = 3.11 ]; then
	mkvenv .venv-bpy45 requirements-bpy45.txt
	mkvenv .venv-bpy43 requirements-bpy43.txt
else
	echo "setup-venv.sh: .venv-bpy45 and .venv-bpy43 skipped: bpy 4.5 and 4.3 have wheels for Python 3.11 only, this machine's is $pyv"
	rm -rf .venv-bpy45 .venv-bpy43
fi
