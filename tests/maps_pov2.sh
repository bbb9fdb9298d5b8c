#!/bin/sh
# export pov --family --maps over two axes with the real POV-Ray (issue 15
# item 3): a 2 x 2 family over epidermis.melanin (log) and dermis.blood
# (lin) (adding-doubling, 7 wavelengths, about 2.5 s), the sphere scene at
# 128 x 128, lit tables of 33 nodes; six renders of about 1 s each.
# Uniform maps at each member render its bake as pov_compare evaluates it
# (<= 0.5 %, as tests/maps_pov.sh); a map with one member per quadrant
# renders each quadrant (away from the edges) within 0.2 % of that member's
# uniform render; a uniform map between the nodes on both axes (t = 0.3
# melanin, 0.6 blood) renders the bilinear blend in t of the four member
# renders, the exporter's stated blend, within 0.2 % per lit pixel.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
CMP="$top_builddir/tests/pov_compare"
SC="$top_srcdir/scenes/sphere.scene"
DATA="$top_srcdir/exporters/pov"
. "$top_srcdir/tests/lib/pov.sh"
pov_require
fam="$tmpd/fam"
# Members: m0000 (melanin 0.01, blood 0.005), m0001 (0.1, 0.005),
# m0002 (0.01, 0.1), m0003 (0.1, 0.1); melanin is axis 0.
check "2 x 2 family over epidermis.melanin and dermis.blood" "$B" bake --preset fair-oily \
	--wavelengths 400:700:50 --theta-nodes 4 --resolution 9x9 --r-bins 50 \
	--vary epidermis.melanin=0.01:0.1:2:log --vary dermis.blood=0.005:0.1:2:lin --out "$fam" --quiet

# render NAME MAPS: export and render into $tmpd/NAME/r.png (16-bit linear).
render() {
	"$B" export pov --scene "$SC" --family "$fam" --maps "$2" --out "$tmpd/$1" --nodes 33 --data-dir "$DATA" \
		>"$tmpd/$1.log" 2>&1 &&
	pov_render "$tmpd/$1" sphere 128 128 >/dev/null
}
for m in 0:0.01:0.005 1:0.1:0.005 2:0.01:0.1 3:0.1:0.1; do
	i=${m%%:*} r=${m#*:} mel=${r%%:*} bl=${r#*:}
	"$B" maps new --family "$fam" --size 16x16 --set epidermis.melanin="$mel" --set dermis.blood="$bl" \
		--out "$tmpd/u$i" --quiet
	if render r$i "$tmpd/u$i"; then
		r=$("$CMP" expect --scene "$SC" --bake "$fam/m000$i" --render "$tmpd/r$i/r.png" --tol 0.005)
		check "uniform maps at member m000$i (melanin $mel, blood $bl): $r (<= 0.5 %)" test $? -eq 0
	else
		fail "uniform maps m000$i: export or render: $(tail -3 "$tmpd/r$i.log" "$tmpd/r$i/pov.log" 2>/dev/null)"
	fi
done
# Quadrant masks (16 x 16 grey PNGs): right half, bottom half (PNG row 0 at the top).
python3 - "$tmpd" <<'PY'
import struct, sys, zlib
def png(path, on):
    w = h = 16
    raw = b''.join(b'\0' + bytes(255 if on(x, y) else 0 for x in range(w)) for y in range(h))
    ch = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    open(path, 'wb').write(b'\x89PNG\r\n\x1a\n' + ch(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0))
        + ch(b'IDAT', zlib.compress(raw)) + ch(b'IEND', b''))
png(sys.argv[1] + '/right.png', lambda x, y: x >= 8)
png(sys.argv[1] + '/bottom.png', lambda x, y: y >= 8)
PY
"$B" maps edit --maps "$tmpd/u0" --set epidermis.melanin=0.1 --mask "$tmpd/right.png" --out "$tmpd/q1" --quiet 2>/dev/null
"$B" maps edit --maps "$tmpd/q1" --set dermis.blood=0.1 --mask "$tmpd/bottom.png" --out "$tmpd/quad-maps" --quiet 2>/dev/null
# Between the nodes: t = 0.3 on the log melanin axis, 0.6 on the blood axis.
mel=$(python3 -c 'print(repr(0.01 * 10 ** 0.3))') bl=$(python3 -c 'print(repr(0.005 + 0.6 * 0.095))')
"$B" maps new --family "$fam" --size 16x16 --set epidermis.melanin="$mel" --set dermis.blood="$bl" \
	--out "$tmpd/mid-maps" --quiet
if render quad "$tmpd/quad-maps" && render mid "$tmpd/mid-maps"; then
	check "each quadrant its member's pixels; between the nodes the bilinear blend" python3 - "$tmpd" <<'PY'
import os, struct, sys, zlib
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_png
def read(path):
    w, h, ch, bits, rows, _ = read_png(path)
    return rows, bits
d = sys.argv[1]
r = [read(d + '/r%d/r.png' % i)[0] for i in range(4)]
q, mid = read(d + '/quad/r.png')[0], read(d + '/mid/r.png')[0]
lit = lambda img, x, y: sum(img[y][x]) > 3000
def region(img, x0, x1, y0, y1):	# mean colour of the lit pixels of [x0, x1) x [y0, y1)
    s = [0, 0, 0]; n = 0
    for y in range(y0, y1):
        for x in range(x0, x1):
            if lit(img, x, y):
                s = [s[c] + img[y][x][c] for c in range(3)]; n += 1
    assert n > 100, n
    return [v / n for v in s]
worst = 0
# Quadrants of the picture, map top = picture top: TL m0000, TR m0001, BL m0002, BR m0003.
for i, (x0, y0) in enumerate(((20, 20), (76, 20), (20, 76), (76, 76))):
    a, b = region(q, x0, x0 + 32, y0, y0 + 32), region(r[i], x0, x0 + 32, y0, y0 + 32)
    e = max(abs(a[c] - b[c]) / b[c] for c in range(3))
    others = min(max(abs(a[c] - o[c]) / o[c] for c in range(3))
                 for o in (region(r[j], x0, x0 + 32, y0, y0 + 32) for j in range(4) if j != i))
    assert e < 0.002 and others > 0.01, ('quadrant', i, a, b, e, others)
    worst = max(worst, e)
# The t the exporter wrote (16-bit map images), then the bilinear blend of the members.
tm = read(d + '/mid/sphere_skin_epidermis.melanin.png')[0][8][8][0] / 65535
tb = read(d + '/mid/sphere_skin_dermis.blood.png')[0][8][8][0] / 65535
assert abs(tm - 0.3) < 1e-4 and abs(tb - 0.6) < 1e-4, (tm, tb)
w = ((1 - tm) * (1 - tb), tm * (1 - tb), (1 - tm) * tb, tm * tb)
emax = esum = n = 0
for y in range(128):
    for x in range(128):
        if not all(lit(img, x, y) for img in r + [mid]):
            continue
        for c in range(3):
            want = sum(w[i] * r[i][y][x][c] for i in range(4))
            e = abs(mid[y][x][c] - want) / want
            emax, esum, n = max(emax, e), esum + e, n + 1
assert n > 3000 and emax < 0.002, (n, emax)
print('# quadrants within %.4f %% of their members; between nodes (t %.4f, %.4f): bilinear blend max %.4f %%, mean %.4f %% over %d values'
      % (100 * worst, tm, tb, 100 * emax, 100 * esum / n, n))
PY
check "the quadrant pigment nests the blood blend over the melanin blend" python3 - "$tmpd/quad/sphere.inc" <<'PY'
import sys
s = open(sys.argv[1]).read()
a, b = s.find('png "sphere_skin_dermis.blood.png"'), s.find('png "sphere_skin_epidermis.melanin.png"')
m = [s.find(']  // ', s.find('SKIN_skin_Pigment_M%04d]' % i)) for i in range(4)]
assert 0 <= a < b < m[0] and s.count('sphere_skin_epidermis.melanin.png') == 2 and 0 < m[0] < m[1] < m[2] < m[3], (a, b, m)
PY
else
	fail "quadrant or between-node map: export or render: $(tail -3 "$tmpd/quad.log" "$tmpd/quad/pov.log" "$tmpd/mid.log" "$tmpd/mid/pov.log" 2>/dev/null)"
fi
tap_done
