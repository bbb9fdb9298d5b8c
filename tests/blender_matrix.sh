#!/bin/sh
# The Blender tests on every Blender the importer claims: each bpy (Blender as a Python module)
# in the venvs that scripts/setup-venv.sh makes ($BPY_PYTHONS: 4.5 LTS and the newest release
# for this machine's Python), run through tests/bpy-blender with the same scripts that test
# Debian's blender (tests/blender_import.sh, tests/blender_lights.sh, tests/blender_translucent.sh:
# each version's own calibrated subsurface fit; tests/blender_eevee.sh
# when SKINBAKE_EEVEE_MATRIX=1: EEVEE Next compiles its shaders in software for 3-4 minutes).
# Each sub-test's lines are reported with the version in front.  A missing venv is skipped
# with a line that says so.  About 4 minutes per version.
. "$top_srcdir/tests/tap.sh"

subtests="blender_import.sh blender_lights.sh blender_translucent.sh maps_blender_translucent.sh"
[ "${SKINBAKE_EEVEE_MATRIX:-0}" = 1 ] && subtests="$subtests blender_eevee.sh"
seen=0
for py in $BPY_PYTHONS; do
	if [ ! -x "$py" ]; then
		skip "$py is missing: scripts/setup.sh makes the bpy venvs (bpy 4.5 only where Python is 3.11)"
		continue
	fi
	ver=$(timeout 120 "$py" -c "import bpy; print(bpy.app.version_string.split()[0])" 2>/dev/null | tail -n 1)
	if [ -z "$ver" ]; then
		fail "$py: import bpy failed"
		continue
	fi
	seen=$((seen + 1))
	for t in $subtests; do
		BLENDER="$top_srcdir/tests/bpy-blender" BPY_PYTHON="$py" sh "$top_srcdir/tests/$t" >"$tmpd/$t.out" 2>&1
		rc=$?
		n=0
		while IFS= read -r line; do
			case $line in
			"ok "*"# SKIP"*) n=$((n + 1)); skip "bpy $ver: $t: ${line#*# SKIP }" ;;
			"not ok "*"# TODO"*) n=$((n + 1)); tap_n=$((tap_n + 1))
				echo "not ok $tap_n - bpy $ver: $t: ${line#not ok [0-9]* - }" ;;
			"ok "*) n=$((n + 1)); ok "bpy $ver: $t: ${line#ok [0-9]* - }" ;;
			"not ok "*) n=$((n + 1)); fail "bpy $ver: $t: ${line#not ok [0-9]* - }" ;;
			esac
		done <"$tmpd/$t.out"
		[ $n -gt 0 ] || fail "bpy $ver: $t ran no check (exit $rc): $(tail -n 3 "$tmpd/$t.out")"
	done
done
[ -n "$BPY_PYTHONS" ] || skip "BPY_PYTHONS is empty (make check sets it to the venvs of scripts/setup-venv.sh)"
echo "# bpy versions tested: $seen; Debian's blender runs the same scripts as tests of their own"
tap_done
