#!/bin/sh
# skinbake maps new|fit|edit|render-albedo on a small family (2 x 2
# members; with adding-doubling a second or two, Monte Carlo longer):
# the round trip made-up maps -> albedo -> fit -> albedo (median CIEDE2000
# under 0.5, parameters within 5 % wherever a 5 % change moves the colour
# by 0.1 CIEDE2000 or more), unmatched and transparent texels flagged,
# masked edits clamped to the family's range, and bad input (sizes, ranges,
# files, format versions) refused with exit 2 and nothing written.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
B="$SKINBAKE"
M="$top_builddir/tests/maps_check"
fam="$tmpd/fam"
"$B" bake --preset fair-oily --wavelengths 400:700:50 --theta-in 0 --resolution 1x1 --target-error 0.05 \
	--batch-photons 1000 --r-bins 50 --vary epidermis.melanin=0.005:0.3:4:log --vary dermis.blood=0.005:0.1:3:log \
	--out "$fam" --quiet || fail "fixture family"

# Pictures for the tests: masks, an albedo with paint and transparent texels.
python3 - "$tmpd" "$fam/family.json" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import write_png as png
d = sys.argv[1]
# a colour of the family: member 5's albedo, sRGB-encoded
enc = lambda v: 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
skin = [enc(v) for v in json.load(open(sys.argv[2]))['members'][5]['albedo_rgb']]
png(d + '/left.png', 96, 64, 1, lambda x, y: (1.0 if x < 48 else 0.0,))
png(d + '/small.png', 32, 32, 1, lambda x, y: (1.0,))
# a family colour with a blue paint square, a black square and a transparent strip
def alb(x, y):
    if y < 4: return (0.5, 0.5, 0.5, 0.0)
    if 10 <= x < 20 and 10 <= y < 20: return (0.1, 0.3, 0.9, 1.0)
    if 30 <= x < 40 and 10 <= y < 20: return (0.02, 0.02, 0.02, 1.0)
    return (skin[0], skin[1], skin[2], 1.0)
png(d + '/paint.png', 96, 64, 4, alb)
PY
printf 'not an image\n' > "$tmpd/notimage.png"

# Interpolation between members against a direct bake off the nodes (issue:
# within the family's own error plus 1 %).
"$M" offnode "$fam" epidermis.melanin=0.05,dermis.blood=0.03 > "$tmpd/off.txt"
sed 's/^/# /' "$tmpd/off.txt"
ov() { awk -v k="$1" '$1 == k { print $2 }' "$tmpd/off.txt"; }
check "off-node: table RMS difference $(ov table_rms_rel_diff) <= family error $(ov family_rms_rel_err) + 0.01" \
	awk "BEGIN { exit !($(ov table_rms_rel_diff) <= $(ov family_rms_rel_err) + 0.01) }"

# Round trip with 16-bit albedos.
check "made-up maps (smooth fields plus freckles)" "$M" synth "$fam" "$tmpd/true" 96 64
check "render-albedo (16-bit PNG)" "$B" maps render-albedo --family "$fam" --maps "$tmpd/true" --out "$tmpd/a.png" --quiet
check "fit" "$B" maps fit --family "$fam" --albedo "$tmpd/a.png" --out "$tmpd/fit" --quiet
check "render-albedo of the fit" "$B" maps render-albedo --family "$fam" --maps "$tmpd/fit" --out "$tmpd/r.png" --quiet
"$M" compare "$fam" "$tmpd/true" "$tmpd/fit" "$tmpd/a.png" "$tmpd/r.png" 0.1 > "$tmpd/cmp.txt"
sed 's/^/# /' "$tmpd/cmp.txt"
val() { awk -v k="$1" '$1 == k { print $2 }' "$tmpd/cmp.txt"; }
check "round trip: median CIEDE2000 $(val de2000_median) < 0.5" awk "BEGIN { exit !($(val de2000_median) < 0.5) }"
for k in epidermis.melanin dermis.blood; do
	check "round trip: $k within 5 % at every sensitive texel ($(val ${k}_sensitive_share) of them; max $(val ${k}_relerr_max))" \
		awk "BEGIN { exit !($(val ${k}_within_5pct_share) == 1 && $(val ${k}_relerr_max) <= 0.05) }"
done
check "maps.json records the fit and the history" python3 -c "
import json; m=json.load(open('$tmpd/fit/maps.json')); f=m['fit']
assert m['format']=='skinbake-maps' and m['width']==96 and m['height']==64 and [x['key'] for x in m['maps']]==['epidermis.melanin','dermis.blood']
assert f['fitted']==96*64 and f['unmatched']==0 and f['de2000_median']<0.5 and m['history'][0].startswith('skinbake maps fit')"

# Unmatched and transparent texels.
check "fit an albedo with paint and a transparent strip" "$B" maps fit --family "$fam" --albedo "$tmpd/paint.png" \
	--out "$tmpd/pfit" --quiet
check "paint flagged unmatched, transparent not fitted, skin matched" python3 -c "
import json, struct, zlib
m=json.load(open('$tmpd/pfit/maps.json'))['fit']
assert m['not_fitted']==4*96, m
assert m['unmatched']==200 and m['de2000_median']<0.5, m
assert m['matched']==m['fitted']-m['unmatched']"

# Edits.
check "maps new" "$B" maps new --family "$fam" --like "$tmpd/left.png" --set dermis.blood=0.02 --out "$tmpd/new" --quiet
"$B" maps edit --maps "$tmpd/new" --scale epidermis.melanin=20 --add dermis.blood=0.01 --mask "$tmpd/left.png" \
	--out "$tmpd/ed" --quiet 2> "$tmpd/ed.err"
check "edit exits 0" [ $? = 0 ]
check "clamping is reported with the family's range" grep -q "epidermis.melanin: 3072 texels (50.00 %) clamped to the family's range \[0.005, 0.3\]" "$tmpd/ed.err"
check "masked edit: left half edited (melanin clamped), right half unchanged" python3 -c "
import json; m=json.load(open('$tmpd/ed/maps.json'))['maps']
mel, bl = m[0]['values'], m[1]['values']
assert abs(mel['max']-0.3)<1e-5 and abs(mel['min']-0.0387298)<1e-5, mel
assert abs(bl['max']-0.03)<1e-5 and abs(bl['min']-0.02)<1e-5, bl"

# Bad input: exit 2, a message naming the file/field/value/expected, nothing written.
bad() {	# DESC PATTERN ARGS...: skinbake ARGS refused (tests/lib/refused.sh)
	b_d=$1 b_p=$2
	shift 2
	refused "$b_d" "$b_p" "$tmpd/bad $tmpd/bad.png $tmpd/bad.staging" "$B" "$@"
}
bad "fit: mask of another size" "small.png is 32 x 32 texels, but --albedo .*a.png is 96 x 64" maps fit \
	--family "$fam" --albedo "$tmpd/a.png" --mask "$tmpd/small.png" --out "$tmpd/bad"
bad "fit: albedo not an image" "notimage.png: not a PNG or OpenEXR image" maps fit --family "$fam" \
	--albedo "$tmpd/notimage.png" --out "$tmpd/bad"
# Limits said before work (issue 23): a 60000 x 60000 PNG (its header only) needs about 144 GB.
python3 -c "
import struct, sys, zlib
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
open(sys.argv[1], 'wb').write(b'\\x89PNG\\r\\n\\x1a\\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 60000, 60000, 8, 2, 0, 0, 0))
    + chunk(b'IDAT', zlib.compress(bytes(100))) + chunk(b'IEND', b''))" "$tmpd/huge.png"
avail=$(awk '/^MemAvailable/ { print $2 }' /proc/meminfo)
if [ -n "$avail" ] && [ "$avail" -lt 100000000 ]; then
	bad "fit: an albedo far larger than the memory is refused at once, with the numbers" \
		"a fit of the 60000 x 60000 texel --albedo needs about [0-9.]* GB of memory (estimated), [0-9.]* GB are available; use a smaller --albedo" \
		maps fit --family "$fam" --albedo "$tmpd/huge.png" --out "$tmpd/bad"
else
	skip "more than 100 GB of memory available: the 60000 x 60000 fit would fit"
fi
# The other subcommands too (src/maps/mapset.h: MAPS_*_MEM_*): new from the size of --like, edit
# and render-albedo from the size maps.json states, before any map is read (72, 86, 144 GB).
if [ -n "$avail" ] && [ "$avail" -lt 70000000 ]; then
	gb="needs about [0-9.]* GB of memory (estimated), [0-9.]* GB are available"
	bad "new: maps far larger than the memory, refused at once with the numbers" \
		"maps new of 60000 x 60000 texels $gb; use a smaller --size" \
		maps new --family "$fam" --like "$tmpd/huge.png" --out "$tmpd/bad"
	cp -r "$tmpd/true" "$tmpd/huge"
	sed -i 's/"width":[0-9]*/"width":60000/; s/"height":[0-9]*/"height":60000/' \
		"$tmpd/huge/maps.json"
	bad "edit: maps.json of 60000 x 60000 texels, refused before the maps are read" \
		"maps edit of 60000 x 60000 texels (--maps .*huge) $gb; edit smaller maps" \
		maps edit --maps "$tmpd/huge" --scale epidermis.melanin=1.3 --out "$tmpd/bad"
	bad "render: maps.json of 60000 x 60000 texels, refused before the maps are read" \
		"maps render-albedo of 60000 x 60000 texels (--maps .*huge) $gb; render smaller" \
		maps render-albedo --family "$fam" --maps "$tmpd/huge" --out "$tmpd/bad.png"
else
	skip "more than 70 GB of memory available: 60000 x 60000 maps would fit"
fi
bad "fit: not a family" "not a family directory" maps fit --family "$tmpd/fit" --albedo "$tmpd/a.png" --out "$tmpd/bad"
cp -r "$fam" "$tmpd/fam2"
sed -i 's/"format_version":1/"format_version":7/' "$tmpd/fam2/family.json"
bad "fit: family of another format version" "family.json: field format_version = 7, expected 1" maps fit \
	--family "$tmpd/fam2" --albedo "$tmpd/a.png" --out "$tmpd/bad"
bad "edit: mask of another size" "small.png is 32 x 32 texels, but the maps .* are 96 x 64" maps edit \
	--maps "$tmpd/new" --scale epidermis.melanin=1.3 --mask "$tmpd/small.png" --out "$tmpd/bad"
bad "edit: set outside the family's range" "set dermis.blood = 0.15 is outside the family's range \[0.005, 0.1\]" \
	maps edit --maps "$tmpd/new" --set dermis.blood=0.15 --out "$tmpd/bad"
bad "edit: unknown map" "dermis.so2: not one of the maps (epidermis.melanin, dermis.blood)" maps edit \
	--maps "$tmpd/new" --scale dermis.so2=2 --out "$tmpd/bad"
bad "edit: negative scale" "scale epidermis.melanin = -1 is out of range \[0, 100\]" maps edit --maps "$tmpd/new" \
	--scale epidermis.melanin=-1 --out "$tmpd/bad"
bad "edit: no edit" "no edit given" maps edit --maps "$tmpd/new" --out "$tmpd/bad"
sed -i 's/"format_version":1/"format_version":3/' "$tmpd/new/maps.json"
bad "edit: maps of another format version" "maps.json: field format_version = 3, expected 1" maps edit \
	--maps "$tmpd/new" --scale epidermis.melanin=1.3 --out "$tmpd/bad"
"$B" bake --preset fair-oily --wavelengths 400:700:50 --theta-in 0 --resolution 1x1 --target-error 0.1 \
	--batch-photons 500 --r-bins 10 --vary epidermis.melanin=0.01:0.05:2:log --vary dermis.blood=0.005:0.1:2:log \
	--out "$tmpd/narrow" --quiet || fail "narrow family"
bad "render: maps outside the family's range" "epidermis.melanin.png: texel (.*) has epidermis.melanin = .*, outside the family's range \[0.01, 0.05\]" \
	maps render-albedo --family "$tmpd/narrow" --maps "$tmpd/true" --out "$tmpd/bad.png"
bad "render: output not .png or .exr" "does not end with .png or .exr" maps render-albedo --family "$fam" \
	--maps "$tmpd/true" --out "$tmpd/bad.tif"
# A full disk (issue 23: "maps fit says 'writing the PNG failed' without the cause"): the K-th
# write fails with ENOSPC (strace): exit 1, the system's message, nothing left.
if command -v strace > /dev/null 2>&1 && strace -f -qq -o /dev/null true 2> /dev/null; then
	full() {	# K ARGS...: skinbake ARGS with its K-th write failing
		k=$1
		shift
		strace -f -qq -o /dev/null -e inject=write:error=ENOSPC:when=$k "$B" "$@"
	}
	nospace='No space left on device'
	for k in 1 3; do
		rm -rf "$tmpd/full" "$tmpd/full.png"
		full $k maps new --family "$fam" --size 8x8 --quiet --out "$tmpd/full" 2> "$tmpd/e"
		rc=$?
		check "maps new, disk full at write $k: exit 1 ($rc), '$(cat "$tmpd/e")', no file" \
			sh -c "[ $rc = 1 ] && grep -q '$nospace' '$tmpd/e' && ! ls -A '$tmpd' |
			grep -q full"
	done
	full 2 maps render-albedo --family "$fam" --maps "$tmpd/true" --out "$tmpd/full.png" \
		--quiet 2> "$tmpd/e"
	rc=$?
	check "render-albedo, disk full: exit 1 ($rc), '$(cat "$tmpd/e")', no file" sh -c \
		"[ $rc = 1 ] && grep -q '$nospace' '$tmpd/e' && [ ! -e '$tmpd/full.png' ]"
else
	skip "strace cannot inject faults here"
fi
tap_done
