#!/bin/sh
# skinbake texture --direction-map: a uniform map turns the furrows like
# --orientation (gray and doubled-angle RGB encodings, docs/relief.md), a
# map of the wrong size or a file that is not a PNG and an unknown site are
# refused with exit status 2, a message naming the option, the value and
# what is allowed, and no output.  Maps: hand, 4.5 mm at 192 px (about 56
# primary junctions: the measured direction of one tile scatters by up to
# 17 degrees over seeds 1-4 with --orientation alone, hence 20 below).
. "$top_srcdir/tests/tap.sh"
S=$SKINBAKE
cd "$tmpd" || exit 1
# mkpng FILE N CHANNELS V0 [V1 V2]: an N x N 16-bit PNG, every pixel the same.
mkpng() {
	python3 - "$@" <<'PY'
import struct, sys, zlib
path, n, ch = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
px = b"".join(struct.pack(">H", int(v)) for v in sys.argv[4:4 + ch])
raw = b"".join(b"\0" + px * n for _ in range(n))
def chunk(t, c):
    return struct.pack(">I", len(c)) + t + c + struct.pack(">I", zlib.crc32(t + c) & 0xffffffff)
hdr = struct.pack(">IIBBBBB", n, n, 16, 0 if ch == 1 else 2, 0, 0, 0)
open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", hdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
PY
}
mkpng d0.png 192 1 0
mkpng d90.png 192 1 32768
mkpng rgb90.png 192 3 0 32768 0
mkpng small.png 64 1 32768
T="--site hand --size 192 --tile-mm 4.5 --stats --quiet"
dir_of() { awk '$1 == "direction_deg" { print $2 }' "$1"; }
# near A B TOL: B is within TOL degrees of A, directions taken modulo 180.
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = (a - b) % 180; if (d < 0) d += 180; if (d > 90) d = 180 - d; exit !(d <= t) }'; }

"$S" texture $T --orientation 90 --out o90 >o90.txt
for m in d0 d90 rgb90; do
	if "$S" texture $T --direction-map $m.png --out $m >$m.txt; then ok "map $m.png runs"; else fail "map $m.png runs"; fi
done
check "manifest names the map" grep -q '"direction_map": *"d90.png"' d90/manifest.json
check "gray 90 deg map: furrows at $(dir_of d90.txt) deg, within 20 of 90" near "$(dir_of d90.txt)" 90 20
check "RGB 90 deg map: furrows at $(dir_of rgb90.txt) deg, within 20 of 90" near "$(dir_of rgb90.txt)" 90 20
check "gray 0 deg map: furrows at $(dir_of d0.txt) deg, within 20 of 0" near "$(dir_of d0.txt)" 0 20
check "--orientation 90 without a map: $(dir_of o90.txt) deg, within 20 of 90" near "$(dir_of o90.txt)" 90 20

# Refusals: status 2, the option and the sizes named, nothing written.
"$S" texture $T --direction-map small.png --out bad1 2>bad1.err
check "map of the wrong size: exit 2" test $? -eq 2
check "message names the option and both sizes" sh -c "grep -q -- '--direction-map' bad1.err && grep -q '64x64' bad1.err && grep -q '192x192' bad1.err"
check "nothing written" test ! -e bad1
echo "not a png" >text.png
"$S" texture $T --direction-map text.png --out bad2 2>bad2.err
check "not a PNG: exit 2 naming the option" sh -c "test $? -eq 2 && grep -q -- '--direction-map: text.png' bad2.err"
check "nothing written" test ! -e bad2
"$S" texture --site elbow --size 64 --stats --out bad3 2>bad3.err
check "site without data: exit 2" test $? -eq 2
check "message names --site, the value and the known sites" sh -c "grep -q -- \"--site: unknown site 'elbow'\" bad3.err && grep -q 'forearm' bad3.err"
check "nothing written" test ! -e bad3
tap_done
