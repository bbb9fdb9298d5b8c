#!/bin/sh
# The relief split in Blender (issue 24, docs/relief.md section 7): in general mode the importer gives
# the subsurface closures normal.png with its slopes blurred by a Gaussian of the set's mean exit
# radius (normal_diffuse.png, three periodic box passes per axis), the surface specular the sharp map.
# Checks:
# - normal_diffuse.png is written and is exactly that blur of normal.png's slopes (the same box
#   passes in numpy, within the 16-bit steps of the two PNGs), and the box width b gives the
#   Gaussian's variance, 3 (b^2 - 1) / 12 = sigma^2, within the rounding of b to an odd integer;
# - SKINBAKE_DIFFUSE_RELIEF=sharp writes none and keeps normal.png;
# - renders (the importer's box scene, 0.125 mm per pixel, Cycles 16 samples): a flat relief renders
#   the same split or sharp; the face relief's relief contrast (RMS about the 5 x 5 local mean, over
#   the mean) is lower split than sharp, and its mean stays within 6 % (first order: the blurred
#   shading is a few % brighter, docs/relief.md measured +3 %; 16 samples' noise adds about 1 %).
# About a minute.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/blender.sh"
. "$top_srcdir/tests/lib/relief.sh"

imp="$top_srcdir/exporters/blender/import_skin.py"
blender_require
# numpy (requirements-test.txt): python3's, else the project's venv.
py=python3
python3 -c 'import numpy' 2>/dev/null || py="$top_srcdir/.venv/bin/python"
relief_bake
relief_textures 128
for t in face flat; do
	"$SKINBAKE" export blender --bake "$bake" --textures "$tmpd/tex-$t" --out "$tmpd/set-$t" >"$tmpd/x-$t.log" 2>&1
	check "export blender --textures $t" test $? -eq 0
	for mode in split sharp; do
		rm -f "$tmpd/set-$t/normal_diffuse.png"
		v=
		test $mode = sharp && v=sharp
		SKINBAKE_FAR=off SKINBAKE_DIFFUSE_RELIEF=$v B --python "$imp" -- "$tmpd/set-$t" --mode general \
			--scene box --res 64 --samples 16 --render "$tmpd/$t-$mode.exr" >"$tmpd/$t-$mode.log" 2>&1
		check "$t relief, $mode diffuse relief: renders" test $? -eq 0
		if [ $mode = split ]; then
			check "$t relief, split: normal_diffuse.png written and reported" \
				sh -c "test -s '$tmpd/set-$t/normal_diffuse.png' && grep -q 'normal_diffuse.png' '$tmpd/$t-$mode.log'"
			test $t = face && cp "$tmpd/set-$t/normal_diffuse.png" "$tmpd/face-diffuse.png"
		else
			check "$t relief, sharp: no normal_diffuse.png" test ! -e "$tmpd/set-$t/normal_diffuse.png"
		fi
	done
done

# The blur, recomputed: the radius and tile from the set's manifest, the box passes in numpy.
out=$("$py" - "$tmpd" <<'PY'
import json, math, os, sys
import numpy as np
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_png
d = sys.argv[1]
m = json.load(open(os.path.join(d, "set-face", "manifest.json")))
def normals(path):
    w, h, ch, bits, rows, _ = read_png(path)
    return np.array(rows, float)[:, :, :3] / (2 ** bits - 1) * 2 - 1
n = normals(os.path.join(d, "set-face", "normal.png"))
got = normals(os.path.join(d, "face-diffuse.png"))
w = n.shape[1]
r = sum(k * float(x) for k, x in zip((0.2126, 0.7152, 0.0722), m["sss_radius_m"]))
sigma = r / math.sqrt(math.pi / 2) / (float(m["detail"]["tile_mm"]) * 1e-3 / w)
b = max(1, int(round(math.sqrt(4 * sigma * sigma + 1))) | 1)
nz = np.maximum(n[:, :, 2], 0.05)
s = [n[:, :, 0] / nz, n[:, :, 1] / nz]
def box(a, axis):
    return sum(np.roll(a, k, axis) for k in range(-(b // 2), b // 2 + 1)) / b
for i in range(2):
    for _ in range(3):
        s[i] = box(box(s[i], 1), 0)
k = 1 / np.sqrt(1 + s[0] ** 2 + s[1] ** 2)
want = np.stack([s[0] * k, s[1] * k, k], 2)
err = np.abs(got - want).max()
var = 3 * (b * b - 1) / 12
# Rounding b to the nearest odd integer moves the variance by at most (b + 1)^2 / 4 - b^2 / 4 = (2b + 1) / 4.
print("%.3g %.4g %.4g %d %.4g %.4g" % (err, var, sigma * sigma, b, (2 * b + 1) / 4,
      np.sqrt(((s[0] ** 2 + s[1] ** 2)).mean()) / np.sqrt(((n[:, :, 0] / nz) ** 2 + (n[:, :, 1] / nz) ** 2).mean())))
PY
)
set -- $out
# Each 16-bit PNG step is 2/65535 in a component: 3e-5 per file, and Blender reads them as floats.
if [ $# -eq 6 ] && awk -v e="$1" 'BEGIN { exit !(e <= 1e-4) }'; then
	ok "normal_diffuse.png = three box passes of width $4 over normal.png's slopes (largest difference $1; RMS slope $6 of the sharp map's)"
else
	fail "normal_diffuse.png vs the box passes: '$out'"
fi
if [ $# -eq 6 ] && awk -v v="$2" -v s="$3" -v t="$5" 'BEGIN { d = v - s; exit !(d <= t && -d <= t) }'; then
	ok "box width $4: variance $2 = sigma^2 $3 within the odd rounding ($5)"
else
	fail "box variance vs sigma^2: '$out'"
fi

out=$(python3 - "$tmpd" <<'PY'
import os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_exr
d = sys.argv[1]
def lum(name):
    e = read_exr(os.path.join(d, name + ".exr"))
    return [[0.2126 * r + 0.7152 * g + 0.0722 * b for r, g, b in zip(*rows)] for rows in zip(e["R"], e["G"], e["B"])]
im = {k: lum(k) for k in ("flat-split", "flat-sharp", "face-split", "face-sharp")}
h, w = len(im["flat-sharp"]), len(im["flat-sharp"][0])
peak = max(v for row in im["flat-sharp"] for v in row)
diff = max(abs(im["flat-split"][y][x] - im["flat-sharp"][y][x]) for y in range(h) for x in range(w)) / peak
# The central part of the box (its top face fills the view), away from the edges.
ys, xs = range(h // 4, 3 * h // 4), range(w // 4, 3 * w // 4)
def contrast(k):
    a = im[k]
    s2 = n = tot = 0
    for y in ys:
        for x in xs:
            loc = sum(a[y + j][x + i] for j in range(-2, 3) for i in range(-2, 3)) / 25
            s2 += (a[y][x] - loc) ** 2
            tot += a[y][x]
            n += 1
    return (s2 / n) ** 0.5 / (tot / n), tot / n
cs, ms = contrast("face-split")
cp, mp = contrast("face-sharp")
print("%.3g %.4g %.4g %.4f" % (diff, cs, cp, ms / mp - 1))
PY
)
set -- $out
if [ $# -eq 4 ] && awk -v d="$1" 'BEGIN { exit !(d <= 1e-4) }'; then
	ok "flat relief: split and sharp render the same (max difference $1 of the peak)"
else
	fail "flat relief: split vs sharp: '$out'"
fi
if [ $# -eq 4 ] && awk -v a="$2" -v b="$3" 'BEGIN { exit !(a < b) }'; then
	ok "face relief: relief contrast split $2 < sharp $3"
else
	fail "face relief: contrast split vs sharp: '$out'"
fi
if [ $# -eq 4 ] && awk -v m="$4" 'BEGIN { exit !(m < 0.06 && m > -0.06) }'; then
	ok "face relief: split mean = sharp mean within 6 % ($4 relative)"
else
	fail "face relief: mean split vs sharp: '$out'"
fi
tap_done
