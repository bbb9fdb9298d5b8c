#!/bin/sh
# The importer's packages in every Blender: `make` built skinbake-blender-extension.zip (4.2+)
# and skinbake-blender-addon.zip (3.x) from exporters/blender/skinbake_import; each Blender
# (Debian's blender, each bpy of $BPY_PYTHONS) validates the extension where it can
# (`blender --command extension validate`; for bpy the same validator, bl_pkg's blender_ext.py
# from the wheel), installs the zip a user would install, lists the package's operators and runs
# File > Import > skinbake image set on the default cube.  A .blend made by Debian's Blender 3.4
# (exact mode) is then opened by each bpy: the material's nodes and links are all there and it
# renders the C value within 1%.  About 1 minute.
. "$top_srcdir/tests/tap.sh"

ext="$top_builddir/skinbake-blender-extension.zip"
addon="$top_builddir/skinbake-blender-addon.zip"
fixture="$top_builddir/tests/blender_fixture"
pkg="$top_srcdir/tests/blender_package.py"
check "make built the extension and add-on zips" test -s "$ext" -a -s "$addon"
check "fixture image set written" "$fixture" "$tmpd/set"

# try_blender LABEL CMD...: install, list, import in one Blender (CMD runs like blender)
try_blender() {
	label=$1
	shift
	u="$tmpd/user-$(echo "$label" | tr -c 'a-zA-Z0-9.\n' _)"
	BLENDER_USER_RESOURCES="$u" BLENDER_USER_SCRIPTS="$u/scripts" BLENDER_USER_CONFIG="$u/config" \
		timeout 300 "$@" -b --factory-startup -noaudio --python-exit-code 1 --python "$pkg" -- \
		"$ext" "$addon" "$tmpd/set/manifest.json" >"$tmpd/pkg.log" 2>&1
	rc=$?
	kind=$(sed -n 's/^SKINBAKE_PACKAGE \([^ ]*\) .*/\1/p' "$tmpd/pkg.log")
	ops=$(sed -n 's/^SKINBAKE_OPERATOR \([^ ]*\) .*/\1/p' "$tmpd/pkg.log" | tr '\n' ' ')
	imp=$(sed -n 's/^SKINBAKE_IMPORT //p' "$tmpd/pkg.log")
	if [ $rc -eq 0 ] && [ -n "$kind" ] && [ -n "$ops" ] && [ "$imp" = "FINISHED skinbake_general" ]; then
		ok "$label: $kind installed, operators: $ops; File > Import on the cube: $imp"
	else
		fail "$label: install/import (exit $rc, kind '$kind', operators '$ops', import '$imp'): $(grep -i error "$tmpd/pkg.log" | head -n 2)"
	fi
}

# 1. Debian's blender.
if [ -n "$BLENDER" ]; then
	dver=$("$BLENDER" --version 2>/dev/null | sed -n 's/^Blender \([0-9.]*\).*/\1/p' | head -n 1)
	case $dver in
	[0-3].* | 4.[01].*)
		skip "Blender $dver: 'blender --command extension validate' does not exist before 4.2 (the add-on zip is the package there)" ;;
	*)
		"$BLENDER" --command extension validate "$ext" >"$tmpd/val.log" 2>&1
		check "Blender $dver: blender --command extension validate: $(tail -n 1 "$tmpd/val.log")" test $? -eq 0 ;;
	esac
	try_blender "Blender $dver (Debian)" "$BLENDER"
else
	skip "blender is missing (BLENDER is empty; the project's set-up installs it)"
fi

# 2. Each bpy.
for py in $BPY_PYTHONS; do
	if [ ! -x "$py" ]; then
		skip "$py is missing: scripts/setup.sh makes the bpy venvs (bpy 4.5 only where Python is 3.11)"
		continue
	fi
	val=$(ls "$(dirname "$py")"/../lib/python3*/site-packages/bpy/*/scripts/addons_core/bl_pkg/cli/blender_ext.py 2>/dev/null | head -n 1)
	ver=$(echo "$val" | sed -n 's|.*/bpy/\([0-9.]*\)/scripts/.*|\1|p')
	if [ -n "$val" ]; then
		"$py" "$val" validate "$ext" >"$tmpd/val.log" 2>&1
		check "bpy $ver: extension validate (bl_pkg's blender_ext.py, as blender --command extension validate): $(tail -n 1 "$tmpd/val.log")" test $? -eq 0
	else
		fail "$py: no bl_pkg/cli/blender_ext.py in its bpy"
	fi
	try_blender "bpy $ver" env BPY_PYTHON="$py" "$top_srcdir/tests/bpy-blender"
done

# 3. A .blend saved by Debian's Blender 3.4, opened by each bpy.
if [ -n "$BLENDER" ] && [ -n "$BPY_PYTHONS" ]; then
	timeout 300 "$BLENDER" -b --factory-startup -noaudio --python-exit-code 1 \
		--python "$top_srcdir/exporters/blender/import_skin.py" -- "$tmpd/set" --mode exact --scene plane \
		--save "$tmpd/old.blend" >"$tmpd/old.log" 2>&1
	check "Blender $dver saved an exact-mode .blend" test $? -eq 0 -a -s "$tmpd/old.blend"
	timeout 300 "$BLENDER" -b "$tmpd/old.blend" --python-exit-code 1 --python "$top_srcdir/tests/blender_scene.py" -- \
		material-summary "skinbake exact" >"$tmpd/sum_old.log" 2>&1
	want=$(sed -n 's/^SKINBAKE_MATERIAL //p' "$tmpd/sum_old.log")
	for py in $BPY_PYTHONS; do
		[ -x "$py" ] || continue
		BPY_PYTHON="$py" timeout 300 "$top_srcdir/tests/bpy-blender" -b "$tmpd/old.blend" --python-exit-code 1 \
			--python "$top_srcdir/tests/blender_scene.py" -- material-summary "skinbake exact" >"$tmpd/sum.log" 2>&1
		bver=$(sed -n 's/^SKINBAKE_VERSION //p' "$tmpd/sum.log")
		got=$(sed -n 's/^SKINBAKE_MATERIAL //p' "$tmpd/sum.log")
		# Blender's own versioning may add nodes (4.0 inserts a Mix node where the Principled
		# BSDF lost its Subsurface Color input) and change a node's type (Glossy BSDF became
		# the Anisotropic one): every node of 3.4 must still be there, under its name.
		lost=$(grep '^SKINBAKE_NODE ' "$tmpd/sum_old.log" | cut -d' ' -f2 | sort >"$tmpd/n_old"; \
			grep '^SKINBAKE_NODE ' "$tmpd/sum.log" | cut -d' ' -f2 | sort >"$tmpd/n_new"; \
			comm -23 "$tmpd/n_old" "$tmpd/n_new" | tr '\n' ' ')
		added=$(grep '^SKINBAKE_NODE ' "$tmpd/sum.log" | sort >"$tmpd/t_new"; grep '^SKINBAKE_NODE ' "$tmpd/sum_old.log" | \
			sort | comm -13 - "$tmpd/t_new" | cut -d' ' -f2,3 | tr '\n' ' ')
		if [ -n "$want" ] && [ -n "$got" ] && [ -z "$lost" ] && [ "${got#*_links_}" = "${want#*_links_}" ]; then
			ok "3.4 .blend in bpy $bver: material intact, all $(wc -l <"$tmpd/n_old") nodes and the images ($got; 3.4: $want; versioning added or changed: ${added:-nothing})"
		else
			fail "3.4 .blend in bpy $bver: material '$got', saved by 3.4 as '$want'; nodes lost: ${lost:-none}"
		fi
		BPY_PYTHON="$py" timeout 300 "$top_srcdir/tests/bpy-blender" -b "$tmpd/old.blend" --python-exit-code 1 \
			--python "$top_srcdir/tests/blender_measure.py" -- "$tmpd/old.exr" >"$tmpd/old_r.log" 2>&1
		got=$(sed -n 's/^SKINBAKE_CENTER //p' "$tmpd/old_r.log")
		r=$(python3 - "$tmpd/set/manifest.json" "$got" <<'PY'
import json, sys
want = json.load(open(sys.argv[1]))["exact"]["reference"]["radiance_rgb"]
got = [float(x) for x in sys.argv[2].split()] if sys.argv[2].strip() else [0, 0, 0]
print(f"{max(abs(g / w - 1) for g, w in zip(got, want)):.2e}")
PY
)
		check "3.4 .blend in bpy $bver: renders the C value (exact mode, compositor sum) within 1%: rel err $r" \
			awk -v r="$r" 'BEGIN { exit !(r <= 0.01) }'
	done
fi
tap_done
