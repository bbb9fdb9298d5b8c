#!/bin/sh
# The split and the fill in POV-Ray (issue 24, docs/relief.md section 7; src/export/pov/povsplit.h):
# a patch of one 8 mm face tile seen head-on (orthographic, 62.5 um per pixel), a parallel light
# at 60 degrees.  Checks:
# - a flat relief is not split, and renders as with --diffuse-relief sharp;
# - the face relief split: its mean as the sharp render's but for the approximation's bias, its
#   relief contrast (RMS of the image minus its 9 x 9 pixel local mean, over the mean) below 0.7 of
#   the sharp one's (the dark paper skin's specular, which keeps the relief, is a large share);
# - the approximation apart from the exporter (numpy): the diffuse shading of the heights blurred
#   by the bake's normalised Rd(r) (luminance-weighted, by FFT) against the physics to first order,
#   the sharp relief's irradiance blurred by it: contrasts within 35 %;
# - the fill: a patch lit from behind shows albedo(0) x fill, albedo the diffuse albedo at
#   normal incidence (the Lambert stand-in) plus the surface specular's (0.01-0.06 for a clear
#   top of index 1.4-1.5).  About 20 s.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/relief.sh"
. "$top_srcdir/tests/lib/pov.sh"
pov_require

relief_bake
relief_textures 256
scene() { # scene FILE LIGHT_Z FILL
	cat >"$1" <<EOF
[scene]
width = 128
height = 128
unit_mm = 1
fill = $3 $3 $3
[camera]
type = orthographic
location = 0 0 -10
look_at = 0 0 0
width = 8
[light key]
type = parallel
position = 1732 0 $2
point_at = 0 0 0
color = 1 1 1
[skin skin]
preset = paper
[object patch]
shape = patch
size = 8 8 1
material = skin
EOF
}
scene "$tmpd/front.scene" -1000 0
scene "$tmpd/back.scene" 1000 0.2
for t in face flat; do
	for m in blurred sharp; do
		"$SKINBAKE" export pov --scene "$tmpd/front.scene" --bake "$bake" --textures "$tmpd/tex-$t" \
			--diffuse-relief $m --out "$tmpd/$t-$m" >"$tmpd/$t-$m.log" 2>&1 &&
			pov_render "$tmpd/$t-$m" front 128 128
		check "export and render, $t relief, diffuse $m" test $? -eq 0
	done
done
check "a flat relief is not split (nothing to blur)" \
	sh -c "! grep -q 'blurred by Rd' '$tmpd/flat-blurred.log' && ! test -f '$tmpd/flat-blurred/front_skin_height_diffuse.png'"
check "the split is said and its blurred height map written" \
	sh -c "grep -q 'blurred by Rd(r)' '$tmpd/face-blurred.log' && test -f '$tmpd/face-blurred/front_skin_height_diffuse.png' \
&& ! grep -q 'blurred by Rd' '$tmpd/face-sharp.log'"
"$SKINBAKE" export pov --scene "$tmpd/back.scene" --bake "$bake" --out "$tmpd/back" >"$tmpd/back.log" 2>&1 &&
	pov_render "$tmpd/back" back 16 16
check "export and render, lit from behind with a fill of 0.2" test $? -eq 0

# numpy (requirements-test.txt): python3's, else the project's venv.
py=python3
python3 -c 'import numpy' 2>/dev/null || py="$top_srcdir/.venv/bin/python"
out=$("$py" - "$tmpd" "$bake" <<'PY'
import json, os, sys
import numpy as np
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_png
d, bake = sys.argv[1], sys.argv[2]
def grey(t):
    w, h, ch, bits, rows, text = read_png(os.path.join(d, t, "r.png"))
    return np.array([[sum(p[:3]) / 3 / 65535 for p in row] for row in rows])
def contrast(a):  # RMS of a minus its 9 x 9 local mean (periodic), over the mean
    k = 9
    m = sum(np.roll(np.roll(a, i - k // 2, 0), j - k // 2, 1) for i in range(k) for j in range(k)) / k ** 2
    return (a - m).std() / a.mean()
fs, fb = grey("flat-sharp"), grey("flat-blurred")
s, b = grey("face-sharp"), grey("face-blurred")
# First-order physics on the tile: heights [um] -> normals -> irradiance n.L (L at 60 degrees in
# x-z, as the render's light), convolved with K(r) from the bake's Rd(r).
w, h, ch, bits, rows, text = read_png(os.path.join(d, "tex-face", "height.png"))
man = json.load(open(os.path.join(d, "tex-face", "manifest.json")))
H = np.array(rows, float)[:, :, 0] / 65535
lo, hi = float(text["skinbake:height_min_um"]), float(text["skinbake:height_max_um"])
H = lo + (hi - lo) * H
n = H.shape[0]
texel = 8000.0 / n
gx = (np.roll(H, -1, 1) - np.roll(H, 1, 1)) / (2 * texel)
gy = (np.roll(H, -1, 0) - np.roll(H, 1, 0)) / (2 * texel)
L = np.array([np.sin(np.pi / 3), 0, np.cos(np.pi / 3)])
E = np.clip((-gx * L[0] - gy * L[1] + L[2]) / np.sqrt(1 + gx ** 2 + gy ** 2), 0, None)
rad = json.load(open(os.path.join(bake, "manifest.json")))["radial"]
rd = np.array(rad["rd_r"], float)
dr = rad["dr_cm"] * 1e4
rgb = np.array(json.load(open(os.path.join(bake, "manifest.json")))["rgb"]["rgb_from_wl"], float) @ rd
rgb /= (rgb * (np.arange(rd.shape[1]) + 0.5)).sum(1, keepdims=True)  # each channel's power 1
prof = np.array([0.2126, 0.7152, 0.0722]) @ rgb
y, x = np.indices((n, n))
r = np.hypot(np.minimum(x, n - x), np.minimum(y, n - y)) * texel
K = np.interp(r, (np.arange(len(prof)) + 0.5) * dr, prof, right=0)
K /= K.sum()
Eb = np.real(np.fft.ifft2(np.fft.fft2(E) * np.fft.fft2(K)))
# the split's approximation: the normals of the blurred heights
Hb = np.real(np.fft.ifft2(np.fft.fft2(H) * np.fft.fft2(K)))
bx = (np.roll(Hb, -1, 1) - np.roll(Hb, 1, 1)) / (2 * texel)
by = (np.roll(Hb, -1, 0) - np.roll(Hb, 1, 0)) / (2 * texel)
Ea = np.clip((-bx * L[0] - by * L[1] + L[2]) / np.sqrt(1 + bx ** 2 + by ** 2), 0, None)
# the pixels (2 texels) sample the maps at their centres
pix = lambda a: 0.25 * (a[::2, ::2] + a[1::2, ::2] + a[::2, 1::2] + a[1::2, 1::2])
c_sharp, c_phys, c_approx = contrast(pix(E)), contrast(pix(Eb)), contrast(pix(Ea))
back = grey("back")
print("%.3g %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.5f" % (np.abs(fs - fb).max(), b.mean() / s.mean() - 1,
      contrast(s), contrast(b), c_sharp, c_phys, c_approx, Ea.mean() / E.mean() - 1, back.mean()))
PY
)
echo "# $out"
set -- $out
if [ $# -eq 9 ] && awk -v d="$1" 'BEGIN { exit !(d < 2e-3) }'; then
	ok "flat relief: renders as with --diffuse-relief sharp (max difference $1)"
else
	fail "flat relief, split vs whole: '$out'"
fi
# The blurred normals lose less light to facets turned from the light than the sharp ones (their
# clipping at 0), so the split is brighter than the physics by the approximation's bias ($8).
if [ $# -eq 9 ] && awk -v m="$2" -v e="$8" 'BEGIN { exit !(m > -0.02 && m < e + 0.02) }'; then
	ok "face relief: the split's mean $2 relative to the sharp render's (the approximation's bias $8)"
else
	fail "face relief, mean split vs sharp: '$out'"
fi
if [ $# -eq 9 ] && awk -v s="$3" -v b="$4" 'BEGIN { exit !(b < 0.7 * s) }'; then
	ok "face relief: relief contrast $4 split, $3 sharp"
else
	fail "face relief, contrast split vs sharp: '$out'"
fi
# The approximation itself (numpy, the bake's Rd(r) by FFT): the diffuse shading of the blurred
# heights against the sharp irradiance convolved with K, both on the same pixels.
if [ $# -eq 9 ] && awk -v p="$6" -v a="$7" 'BEGIN { exit !(a < 1.35 * p && a > p / 1.35) }'; then
	ok "first order: blurred normals' contrast $7 within 35 % of the blurred irradiance's $6 (sharp $5)"
else
	fail "first order, blurred normals vs blurred irradiance: '$out'"
fi
lam=$(sed -n 's/.*SKIN_skin_Lambert = texture { pigment { rgb <\([^,]*\),\([^,]*\),\([^>]*\)>.*/\1 \2 \3/p' \
	"$tmpd/back/back.inc")
if [ $# -eq 9 ] && [ -n "$lam" ] && echo "$lam" | awk -v v="$9" '{ s = (v / 0.2) - ($1 + $2 + $3) / 3;
    exit !(s > 0.01 && s < 0.06) }'; then
	ok "fill: lit from behind the patch shows albedo x 0.2 ($9; the diffuse albedo $lam and a specular one)"
else
	fail "fill: '$out', Lambert albedo '$lam'"
fi
tap_done
