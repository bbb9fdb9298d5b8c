#!/bin/sh
# The relief's far roughness in Blender (issue 24 item 3, docs/relief.md section 6): a sphere whose
# face relief is far below a pixel (Cycles, general mode, 3.6 mm per pixel, 0.35 mm cells).  With
# roughness_far.png the importer fades the normal map out and adds alpha_relief to the specular
# roughness in quadrature; SKINBAKE_FAR=off leaves the normal map alone.  Checks: a flat relief
# (alpha_relief 0 everywhere) renders the same either way; the face relief's far render keeps the
# mean of the near one (the spread of its normals, only as roughness) within 3 %, with less
# pixel-to-pixel noise, and its highlight is lower than the flat relief's.  About 40 s.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/blender.sh"
. "$top_srcdir/tests/lib/relief.sh"

imp="$top_srcdir/exporters/blender/import_skin.py"
blender_require
relief_bake
relief_textures 256
for t in face flat; do
	"$SKINBAKE" export blender --bake "$bake" --textures "$tmpd/tex-$t" --out "$tmpd/set-$t" >"$tmpd/x-$t.log" 2>&1
	check "export blender --textures $t copies roughness_far.png" test -f "$tmpd/set-$t/roughness_far.png"
	for far in on off; do
		SKINBAKE_FAR=$far B --python "$imp" -- "$tmpd/set-$t" --mode general --scene sphere --res 64 --samples 16 \
			--render "$tmpd/$t-$far.exr" >"$tmpd/$t-$far.log" 2>&1
		check "$t relief, far $far renders" test $? -eq 0
	done
done
out=$(python3 - "$tmpd" <<'PY'
import os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_exr
d = sys.argv[1]
def grey(name):
    e = read_exr(os.path.join(d, name + ".exr"))
    return [[(r + g + b) / 3 for r, g, b in zip(*rows)] for rows in zip(e["R"], e["G"], e["B"])]
im = {k: grey(k) for k in ("flat-on", "flat-off", "face-on", "face-off")}
mask = [(y, x) for y, row in enumerate(im["flat-off"]) for x, v in enumerate(row) if v > 1e-4]
peak = max(v for row in im["flat-off"] for v in row)
diff = max(abs(im["flat-on"][y][x] - im["flat-off"][y][x]) for y, x in mask) / peak
mean = lambda k: sum(im[k][y][x] for y, x in mask) / len(mask)
def noise(k):
    a = im[k]
    s = [abs(a[y][x] - a[y][x + 1]) for y, x in mask if x + 1 < len(a[y]) and a[y][x + 1] > 1e-4]
    return sum(s) / len(s)
def p995(k):
    v = sorted(im[k][y][x] for y, x in mask)
    return v[int(0.995 * (len(v) - 1))]
print("%.3g %.5f %.4g %.4g %.4g %.4g %.4g" % (diff, mean("face-on") / mean("face-off") - 1, noise("face-on"),
      noise("face-off"), p995("face-on"), p995("flat-on"), len(mask)))
PY
)
set -- $out
if [ $# -eq 7 ] && awk -v d="$1" 'BEGIN { exit !(d <= 1e-4) }'; then
	ok "flat relief: far on and off render the same (max difference $1 of the peak, $7 px)"
else
	fail "flat relief: far on vs off: '$out'"
fi
if [ $# -eq 7 ] && awk -v m="$2" 'BEGIN { exit !(m < 0.03 && m > -0.03) }'; then
	ok "face relief: far mean = near mean ($2 relative)"
else
	fail "face relief: far mean vs near: '$out'"
fi
if [ $# -eq 7 ] && awk -v a="$3" -v b="$4" 'BEGIN { exit !(a < b) }'; then
	ok "face relief: far render less noisy than the normal map at 16 samples ($3 < $4)"
else
	fail "face relief: noise far vs near: '$out'"
fi
if [ $# -eq 7 ] && awk -v a="$5" -v b="$6" 'BEGIN { exit !(a < 0.95 * b) }'; then
	ok "face relief: far highlight (99.5th percentile $5) below the flat relief's ($6)"
else
	fail "face relief: far highlight vs flat: '$out'"
fi
tap_done
