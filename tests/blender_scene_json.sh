#!/bin/sh
# The Blender importer's --scene-json (camera and lights from scene.json of `skinbake scene`)
# against the real POV-Ray on the same scene file, with Debian's Blender (Cycles CPU, direct
# light only, point-sampled pixels, as POV-Ray without antialiasing): two plain spheres
# (tests/blender_scene.py make-scene-json builds them), 80 x 60 px.
#   A: an off-axis perspective camera, two parallel lights of different colours;
#   B: an orthographic camera, one point light (Blender's falls off as 1/d^2, the scene file's
#      does not: scene-compare takes the falloff out per pixel).
# Silhouettes: lit pixels agree but for at most 2 % of them, centroids within 0.1 px (a mirrored,
# shifted or mis-scaled camera moves them; measured 1 of 1098 and 11 of 875 pixels, within 0.03 px;
# the probe with the camera mirrored in x: 172 pixels).  Shading: pi x Blender's radiance against
# POV-Ray's pixel (docs/scene-json.md) over 2 x 2 blocks off the edges, mean within 0.5 %, 90th
# percentile within 1 % (the mesh sphere's interpolated normals: under 1 %; measured mean 0.07 %
# and 0.05 %, p90 0.2 % and 0.08 %).  Bad input exits 2.  About 30 s of CPU, 7 Blender starts.
. "$top_srcdir/tests/tap.sh"

imp="$top_srcdir/exporters/blender/import_skin.py"
scn="$top_srcdir/tests/blender_scene.py"
. "$top_srcdir/tests/lib/pov.sh"
. "$top_srcdir/tests/lib/blender.sh"
pov_require
if [ -z "$BLENDER" ] || ! command -v "$BLENDER" >/dev/null 2>&1; then
	fail "blender is missing (BLENDER='$BLENDER'; the project's set-up installs it)"
	tap_done
	exit 1
fi
B() { timeout 300 "$BLENDER" -b -noaudio --python-exit-code 1 "$@"; }

# The importer needs an image set (its material is made, on no object).
"$SKINBAKE" bake --preset paper --out "$tmpd/bake" --theta-nodes 3 --resolution 5x5 --r-bins 10 \
	--radial-photons 2000 --quiet >"$tmpd/bake.log" 2>&1
"$SKINBAKE" export blender --bake "$tmpd/bake" --out "$tmpd/set" --lut-cos 8 --lut-phi 3 --mode exact >"$tmpd/export.log" 2>&1
check "image set exported" test -f "$tmpd/set/manifest.json"

spheres='
[object big]
shape = sphere
radius = 1
material = plain
color = 0.8 0.8 0.8

[object small]
shape = sphere
center = 1.6 -0.5 -0.4
radius = 0.4
material = plain
color = 0.5 0.7 0.3
'
cat >"$tmpd/A.scene" <<EOF
[scene]
width = 80
height = 60
unit_mm = 10

[camera]
type = perspective
location = 1.5 2 -6
look_at = 0.2 0 0
angle = 40

[light key]
type = parallel
position = 1000 800 -600
color = 0.7 0.6 0.5

[light fill]
type = parallel
position = -900 -100 -700
color = 0.1 0.2 0.3
$spheres
EOF
cat >"$tmpd/B.scene" <<EOF
[scene]
width = 80
height = 60
unit_mm = 10

[camera]
type = orthographic
location = -1 1.5 -8
look_at = 0.3 0 0
width = 4.2

[light bulb]
type = point
position = -3 1 -2
color = 0.2 0.3 0.4
$spheres
EOF

for s in A B; do
	dir="$tmpd/$s"
	mkdir -p "$dir"
	"$SKINBAKE" scene --scene "$tmpd/$s.scene" --out "$dir/scene.json" >"$dir/scene.log" 2>&1 &&
		"$SKINBAKE" export pov --scene "$tmpd/$s.scene" --out "$dir/pov" --data-dir "$top_srcdir/exporters/pov" \
			>"$dir/pov.log" 2>&1 &&
		pov_render "$dir/pov" $s 80 60 >/dev/null
	check "$s: scene.json written, POV-Ray rendered the export" test -s "$dir/pov/r.png" -a -s "$dir/scene.json"
	B --factory-startup --python "$scn" -- make-scene-json "$dir/scene.json" "$dir/balls.blend" >"$dir/make.log" 2>&1
	B "$dir/balls.blend" --python "$imp" -- "$tmpd/set" --scene-json "$dir/scene.json" --render "$dir/b.exr" \
		--save "$dir/out.blend" >"$dir/imp.log" 2>&1
	check "$s: imported camera and lights, rendered ($(grep -c 'from .*scene.json' "$dir/imp.log") note)" \
		test -s "$dir/b.exr" -a -s "$dir/out.blend"
	B "$dir/out.blend" --python "$scn" -- scene-compare "$dir/b.exr" "$dir/pov/r.png" "$dir/scene.json" >"$dir/cmp.log" 2>&1
	set -- $(val SKINBAKE_SILHOUETTE "$dir/cmp.log")
	check "$s: silhouettes: ${1:-?} of ${3:-?} lit pixels differ (<= 2 %), centroid off by ${4:-?}, ${5:-?} px (<= 0.1)" \
		awk -v b="${1:-1e9}" -v n="${3:-0}" -v x="${4:-1e9}" -v y="${5:-1e9}" \
		'BEGIN { exit !(n > 100 && b <= 0.02 * n && x * x <= 0.01 && y * y <= 0.01) }'
	set -- $(val SKINBAKE_SHADING "$dir/cmp.log")
	check "$s: pi x Blender vs POV-Ray over ${1:-?} blocks: mean ${2:-?}, p90 ${3:-?} (<= 0.005, 0.01)" \
		awk -v n="${1:-0}" -v m="${2:-1}" -v p="${3:-1}" 'BEGIN { exit !(n >= 40 && m <= 0.005 && p <= 0.01) }'
done
# The frame really is what makes them agree: the same import with x mirrored misses.
sed 's/location = 1.5 2 -6/location = -1.5 2 -6/' "$tmpd/A.scene" >"$tmpd/M.scene"
"$SKINBAKE" scene --scene "$tmpd/M.scene" --out "$tmpd/M.json" >/dev/null 2>&1
B "$tmpd/A/balls.blend" --python "$imp" -- "$tmpd/set" --scene-json "$tmpd/M.json" --render "$tmpd/m.exr" \
	--save "$tmpd/m.blend" >"$tmpd/m.log" 2>&1
B "$tmpd/m.blend" --python "$scn" -- scene-compare "$tmpd/m.exr" "$tmpd/A/pov/r.png" "$tmpd/M.json" >"$tmpd/mc.log" 2>&1
set -- $(val SKINBAKE_SILHOUETTE "$tmpd/mc.log")
check "probe: a camera mirrored in x is caught (${1:-?} pixels differ, centroid ${4:-?} px off)" \
	awk -v b="${1:-0}" -v n="${3:-1}" 'BEGIN { exit !(b > 0.02 * n) }'

# Bad input: not a scene.json; --scene-json with a demo scene.
echo '{"format": "skinbake-blender-image-set"}' >"$tmpd/bad.json"
B --factory-startup --python "$imp" -- "$tmpd/set" --scene-json "$tmpd/bad.json" >"$tmpd/bad.log" 2>&1
rc=$?
check "not a scene.json: exit 2 naming it ($(grep -o 'error: .*' "$tmpd/bad.log" | head -1))" \
	sh -c "[ $rc -eq 2 ] && grep -q 'is not a skinbake scene' '$tmpd/bad.log'"
B --factory-startup --python "$imp" -- "$tmpd/set" --scene sphere --scene-json "$tmpd/A/scene.json" \
	--render "$tmpd/x.png" >"$tmpd/bad2.log" 2>&1
rc=$?
check "--scene sphere with --scene-json: exit 2, nothing rendered" \
	sh -c "[ $rc -eq 2 ] && [ ! -e '$tmpd/x.png' ] && grep -q 'scene-json' '$tmpd/bad2.log'"
tap_done
