#!/bin/sh
# Every read of a bake is checked against its manifest (issue 23 item 4,
# src/bake/manifest_check.c, src/base/checksum.c): tampered manifests
# (numbers as text, descending or infinite axes, out-of-range specular,
# zero indices, repeated wavelengths, NaN weights, wrong table sizes) and
# changed data files (30 single-byte flips spread over brdf_rgb.exr, each
# caught by its SHA-256 in the manifest) are refused by eval with exit
# status 2 and a message naming the file, the key and the value; verify and
# both exporters refuse them the same way; texture, family and maps
# directories carry checksums too.  Costs about 10 s.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
T=$top_srcdir
cd "$tmpd" || exit 1
"$B" bake --preset paper --solver ad --theta-nodes 3 --resolution 9x6 --radial-error 0.2 --r-bins 20 --out bk \
	--quiet || fail "good bake"
"$B" texture --size 16 --out tx --quiet || fail "good texture"
EVAL="eval --theta-in 30 --theta-out 20 --phi 90"
check "the good bake is read" sh -c "'$B' $EVAL --bake bk > /dev/null"
check "every data file has its checksum in the manifest" python3 -c "
import json; m = json.load(open('bk/manifest.json'))
assert sorted(m['checksums']) == ['albedo.exr', 'albedo.png', 'brdf.exr', 'brdf_rgb.exr'], m['checksums']"

# bad DESC PATTERN CMD...: exit 2, stderr matches PATTERN (grep -E), no output directory o*
# (tests/lib/refused.sh)
. "$top_srcdir/tests/lib/refused.sh"
refused_ere=1
bad() {
	b_d=$1 b_p=$2
	shift 2
	refused "$b_d" "$b_p" "o_*" "$@"
}

# tamper DESC PATTERN PYTHON: edit t/manifest.json (m) with PYTHON; eval refuses it
tamper() {
	rm -rf t && cp -r bk t
	python3 -c "
import json, math; p = 't/manifest.json'; m = json.load(open(p))
$3
open(p, 'w').write(json.dumps(m, indent=1))" || { fail "$1: the edit failed"; return; }
	bad "manifest: $1" "t/(manifest.json|brdf.exr): $2" "$B" $EVAL --bake t
}
tamper "theta_i as text" "theta_i_deg\[0\] = \"0(.0)?\" is not a number" "m['theta_i_deg'] = [str(x) for x in m['theta_i_deg']]"
tamper "theta_i descending" "theta_i_deg\[2\] = 30 is not above theta_i_deg\[1\] = 60 \(the axis must ascend\)" \
	"m['theta_i_deg'] = [0, 60, 30]"
tamper "theta_i 1e999" "theta_i_deg\[2\] = inf is out of range|theta_i_deg\[2\] = .* is not a number" \
	"m['theta_i_deg'][2] = float('inf')"
tamper "specular alpha -5" "specular.alpha = -5 is out of range \[0.01, 1\]" "m['specular']['alpha'] = -5"
tamper "stack_n zeros" "specular.stack_n\[0\]\[0\] = 0 is out of range \[1, 3\]" \
	"m['specular']['stack_n'][0] = [0 for x in m['specular']['stack_n'][0]]"
tamper "a repeated wavelength" "wavelengths_nm\[1\] = 470 repeats wavelengths_nm\[0\] = 470" \
	"m['wavelengths_nm'] = [470, 470, 656]"
tamper "rgb_from_wl NaN" "rgb.rgb_from_wl\[1\]\[0\] = (nan|NaN) is out of range|rgb_from_wl\[1\]\[0\] = NaN is not" \
	"m['rgb']['rgb_from_wl'][1][0] = float('nan')"
tamper "a table height the files do not have" "6 x 27, but manifest.json's axes make it 6 x 30" \
	"m['theta_o_centres_deg'].append(89.9)"
tamper "format_version as text" "format_version = \"1\" is not a number" "m['format_version'] = '1'"
tamper "a radius row too short" "radial.mean_radius_cm has 2 entries; allowed 3 to 3" \
	"m['radial']['mean_radius_cm'] = m['radial']['mean_radius_cm'][:2]"
tamper "a checksum that leaves the directory" "checksums.../manifest.json: not a file of the directory" \
	"m['checksums']['../manifest.json'] = m['checksums']['brdf.exr']"

# Byte flips spread over brdf_rgb.exr: each one is caught.
size=$(wc -c < bk/brdf_rgb.exr)
caught=0
k=1
while [ $k -le 30 ]; do
	rm -rf t && cp -r bk t
	python3 -c "
p = 't/brdf_rgb.exr'; b = bytearray(open(p, 'rb').read()); i = $k * (len(b) - 1) // 31
b[i] ^= 0x10; open(p, 'wb').write(b)"
	"$B" $EVAL --bake t > /dev/null 2> err.txt
	[ $? -eq 2 ] && grep -q "t/brdf_rgb.exr has changed since its manifest was written" err.txt && caught=$((caught + 1))
	k=$((k + 1))
done
check "30 single-byte flips over brdf_rgb.exr ($size bytes): $caught refused by their checksum" [ $caught -eq 30 ]

# The other readers of a bake refuse the same damage.
rm -rf t && cp -r bk t && printf 'x' >> t/brdf.exr
bad "verify refuses a changed brdf.exr" "t/brdf.exr has changed" "$B" verify --bake t --cells 2 --photons 1000
bad "export pov refuses a changed brdf.exr" "t/brdf.exr has changed" \
	"$B" export pov --bake t --scene "$T/scenes/sphere.scene" --out o_pov
bad "export blender refuses a changed brdf.exr" "t/brdf.exr has changed" \
	"$B" export blender --bake t --out o_bl --lut-cos 8 --lut-phi 3
rm -rf t && cp -r bk t && python3 -c "
import json; p = 't/manifest.json'; m = json.load(open(p)); m['theta_i_deg'] = [0, 60, 30]
open(p, 'w').write(json.dumps(m))"
bad "export blender refuses a descending axis" "theta_i_deg\[2\] = 30 is not above" \
	"$B" export blender --bake t --out o_bl --lut-cos 8 --lut-phi 3

# Texture directories: height.png changed after the manifest.
rm -rf t && cp -r tx t && printf 'x' >> t/height.png
bad "export blender refuses a changed texture height.png" "t/height.png has changed" \
	"$B" export blender --bake bk --textures t --out o_bl --lut-cos 8 --lut-phi 3
check "texture, export blender and export pov manifests carry checksums" sh -c "
	'$B' export blender --bake bk --textures tx --out bl --lut-cos 8 --lut-phi 3 > /dev/null &&
	'$B' export pov --bake bk --scene '$T/scenes/sphere.scene' --out pv > /dev/null 2>&1 &&
	grep -q '\"height.png\": \"sha256:' tx/manifest.json && grep -q '\"brdf_lut.exr\": \"sha256:' bl/manifest.json &&
	grep -q '\"sphere.inc\": \"sha256:' pv/manifest.json"
tap_done
