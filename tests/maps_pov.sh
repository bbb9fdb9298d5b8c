#!/bin/sh
# export pov --family --maps with the real POV-Ray (issue 15 item 3): a
# 3-member family over dermis.blood (adding-doubling, 7 wavelengths, about
# 2 s), maps from `maps new`/`maps edit`, the sphere scene (one parallel
# light, orthographic camera) at 128 x 128, lit tables of 33 nodes; four
# renders of about 1 s each.  Uniform maps at a member's value render that
# member's bake as pov_compare evaluates it in C (<= 0.5 %, as a plain
# export); a map with high blood on its right half shows a redder right
# half whose pixels are the high-blood member's, the left half the
# low-blood member's (<= 0.2 % away from the edge); bad input exits 2.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
B="$SKINBAKE"
CMP="$top_builddir/tests/pov_compare"
SC="$top_srcdir/scenes/sphere.scene"
DATA="$top_srcdir/exporters/pov"
. "$top_srcdir/tests/lib/pov.sh"
pov_require
fam="$tmpd/fam"
check "family over dermis.blood" "$B" bake --preset fair-oily --wavelengths 400:700:50 --theta-nodes 4 \
	--resolution 9x9 --r-bins 50 --vary dermis.blood=0.005,0.03,0.1 --out "$fam" --quiet

# export NAME MAPS: export and render into $tmpd/NAME/r.png (16-bit linear).
render() {
	"$B" export pov --scene "$SC" --family "$fam" --maps "$2" --out "$tmpd/$1" --nodes 33 --data-dir "$DATA" \
		>"$tmpd/$1.log" 2>&1 &&
	pov_render "$tmpd/$1" sphere 128 128 >/dev/null
}
for m in 0:0.005 1:0.03 2:0.1; do
	i=${m%%:*} v=${m#*:}
	"$B" maps new --family "$fam" --size 16x16 --set dermis.blood="$v" --out "$tmpd/u$i" --quiet
	if render r$i "$tmpd/u$i"; then
		r=$("$CMP" expect --scene "$SC" --bake "$fam/m000$i" --render "$tmpd/r$i/r.png" --tol 0.005)
		check "uniform map dermis.blood = $v renders member m000$i: $r (<= 0.5 %)" test $? -eq 0
	else
		fail "uniform map $v: export or render: $(tail -3 "$tmpd/r$i.log" "$tmpd/r$i/pov.log" 2>/dev/null)"
	fi
done
check "the export names the coordinate map" [ -s "$tmpd/r1/sphere_skin_dermis.blood.png" ]
check "the pigment blends the members by the map" grep -q 'image_pattern { png "sphere_skin_dermis.blood.png" gamma 1.0' \
	"$tmpd/r1/sphere.inc"

# Right half of the map at the family's highest blood, left half at the lowest.
python3 - "$tmpd/right.png" <<'PY'
import struct, sys, zlib
w = h = 16
raw = b''.join(b'\0' + bytes(255 if x >= w // 2 else 0 for x in range(w)) for y in range(h))
ch = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
open(sys.argv[1], 'wb').write(b'\x89PNG\r\n\x1a\n' + ch(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0))
    + ch(b'IDAT', zlib.compress(raw)) + ch(b'IEND', b''))
PY
"$B" maps edit --maps "$tmpd/u0" --set dermis.blood=0.1 --mask "$tmpd/right.png" --out "$tmpd/painted-maps" --quiet 2>/dev/null
if render painted "$tmpd/painted-maps"; then
	check "painted blood: right half redder, each half its member's pixels" python3 - "$tmpd" <<'PY'
import os, struct, sys, zlib
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_png
def read(path):
    w, h, ch, bits, rows, _ = read_png(path)
    assert bits == 16 and ch == 3
    return rows
d = sys.argv[1]
p, lo, hi = read(d + '/painted/r.png'), read(d + '/r0/r.png'), read(d + '/r2/r.png')
def region(img, x0, x1):	# lit pixels of the columns [x0, x1)
    s = [0, 0, 0]; n = 0
    for y in range(128):
        for x in range(x0, x1):
            if sum(img[y][x]) > 3000:
                s = [s[c] + img[y][x][c] for c in range(3)]; n += 1
    return [v / n for v in s]
L, R = region(p, 20, 52), region(p, 76, 108)
redness = lambda c: c[0] / c[1]
assert redness(R) > redness(L) * 1.05, (L, R)
for a, b in ((L, region(lo, 20, 52)), (R, region(hi, 76, 108))):
    e = max(abs(a[c] - b[c]) / b[c] for c in range(3))
    assert e < 0.002, (a, b, e)
print('# R/G left %.4f right %.4f' % (redness(L), redness(R)))
PY
else
	fail "painted map: export or render: $(tail -3 "$tmpd/painted.log" "$tmpd/painted/pov.log" 2>/dev/null)"
fi

bad() {	# DESC PATTERN ARGS...: export pov ARGS refused (tests/lib/refused.sh)
	b_d=$1 b_p=$2
	shift 2
	refused "$b_d" "$b_p" "$tmpd/bad" "$B" export pov "$@" --out "$tmpd/bad"
}
bad "--family without --maps" "go together" --scene "$SC" --family "$fam"
bad "--family with --bake" "not with\|excl\|--bake" --scene "$SC" --family "$fam" --maps "$tmpd/u0" --bake "$fam/m0000"
"$B" bake --preset fair-oily --wavelengths 400:700:100 --theta-nodes 2 --resolution 3x3 --r-bins 10 \
	--vary epidermis.melanin=0.01,0.1 --out "$tmpd/fam2" --quiet
"$B" maps new --family "$tmpd/fam2" --size 4x4 --out "$tmpd/m2" --quiet
bad "maps of another family" "map 0 is epidermis.melanin" --scene "$SC" --family "$fam" --maps "$tmpd/m2"
bad "two lights" "maps take one light" --scene "$top_srcdir/scenes/two-lights.scene" --family "$fam" --maps "$tmpd/u0"
bad "not a maps directory" "maps.json" --scene "$SC" --family "$fam" --maps "$fam"
tap_done
