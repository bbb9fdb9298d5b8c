#!/bin/sh
# maps fit streams its files (maps_fit_files: the albedo and mask read in
# bands of 64 rows, the maps written band by band, from the colour ids
# kept by the first reading or, for large albedos, from a second reading):
# the same files, byte for byte, as the in-memory path (maps_check
# fit-memory: image_read, maps_fit, mapset_write) for 16-bit PNG and
# linear EXR albedos, PNG and EXR maps, transparent texels and a mask, on
# 150 rows (two whole bands and a part), both ways (maps_check fit-reread
# forces the second reading); a truncated or corrupt albedo is refused
# with exit 2 and leaves the maps it would replace as they were.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
M="$top_builddir/tests/maps_check"
fam="$tmpd/fam"
"$B" bake --preset fair-oily --wavelengths 400:700:50 --theta-in 0 --resolution 1x1 --target-error 0.05 \
	--batch-photons 1000 --r-bins 50 --vary epidermis.melanin=0.005:0.3:4:log --vary dermis.blood=0.005:0.1:3:log \
	--out "$fam" --quiet || fail "fixture family"
"$M" synth "$fam" "$tmpd/true" 96 150 > /dev/null || fail "made-up maps"
"$B" maps render-albedo --family "$fam" --maps "$tmpd/true" --out "$tmpd/a.png" --quiet || fail "albedo PNG"
"$B" maps render-albedo --family "$fam" --maps "$tmpd/true" --out "$tmpd/a.exr" --quiet || fail "albedo EXR"
"$M" noise "$tmpd/a.png" "$tmpd/n.png" 40 || fail "noisy albedo"
# an RGBA albedo with a transparent strip and a mask of the left half (16-bit
# grey + alpha and 8-bit grey PNGs written here)
python3 - "$tmpd" <<'PY'
import os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import write_png as png
d = sys.argv[1]
png(d + '/mask.png', 96, 150, 1, lambda x, y: (1.0 if x < 48 else 0.0,), 8)
png(d + '/alpha.png', 96, 150, 2, lambda x, y: (0.55 + 0.1 * ((x * 7 + y * 3) % 11) / 11, 0.0 if 70 <= y < 75 else 1.0), 16)
PY
# same DIR1 DIR2: every file byte for byte, maps.json but for seconds and history
same() {
	for f in $(ls "$1"); do
		[ "$f" = maps.json ] && continue
		cmp -s "$1/$f" "$2/$f" || { echo "# $f differs"; return 1; }
	done
	[ "$(ls "$1")" = "$(ls "$2")" ] || { echo "# other files"; return 1; }
	python3 - "$1/maps.json" "$2/maps.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for j in (a, b):
    j.pop('history'); j.pop('checksums', None); j['fit'].pop('seconds'); j['fit'].pop('albedo')
sys.exit(a != b)
PY
}
for case in "a.png png" "a.png exr" "a.exr png" "a.exr exr" "n.png png" "alpha.png png mask.png" \
	"a.png exr mask.png"; do
	set -- $case
	alb=$1 fmt=$2 mask=${3:-}
	name=$(echo "$case" | tr ' .' '__')
	"$M" fit-memory "$fam" "$tmpd/$alb" "$tmpd/mem_$name" "$fmt" ${mask:+"$tmpd/$mask"} || fail "in-memory fit $case"
	check "fit $alb to $fmt maps${mask:+ with $mask}: streamed and in-memory files identical" sh -c "
		'$B' maps fit --family '$fam' --albedo '$tmpd/$alb' --format $fmt ${mask:+--mask '$tmpd/$mask'} \
			--out '$tmpd/str_$name' --quiet"
	check "  ... byte for byte" same "$tmpd/mem_$name" "$tmpd/str_$name"
	check "  ... and with one thread" sh -c "'$B' maps fit --family '$fam' --albedo '$tmpd/$alb' --format $fmt \
		${mask:+--mask '$tmpd/$mask'} --threads 1 --out '$tmpd/one_$name' --quiet"
	check "  ... byte for byte" same "$tmpd/mem_$name" "$tmpd/one_$name"
	check "  ... reading the albedo twice" "$M" fit-reread "$fam" "$tmpd/$alb" "$tmpd/two_$name" "$fmt" \
		${mask:+"$tmpd/$mask"}
	check "  ... byte for byte" same "$tmpd/mem_$name" "$tmpd/two_$name"
done
# A corrupt albedo: its header is fine (the size check passes), its rows are
# not; the fit finds it while reading and leaves the maps it would replace.
cp -r "$tmpd/str_a_png_png" "$tmpd/keep"
ls -l "$tmpd/keep" | md5sum > "$tmpd/keep.sum"
cat "$tmpd"/keep/* | md5sum >> "$tmpd/keep.sum"
size=$(wc -c < "$tmpd/a.png")
head -c $((size / 2)) "$tmpd/a.png" > "$tmpd/trunc.png"
python3 - "$tmpd/a.png" "$tmpd/flip.png" <<'PY'
import sys
b = bytearray(open(sys.argv[1], 'rb').read())
i = b.index(b'IDAT') + 4 + 2000	# inside the compressed rows: the CRC fails
b[i] ^= 0xff
open(sys.argv[2], 'wb').write(bytes(b))
PY
for bad in trunc flip; do
	"$B" maps fit --family "$fam" --albedo "$tmpd/$bad.png" --out "$tmpd/keep" --quiet 2> "$tmpd/e"
	rc=$?
	check "fit of a $bad albedo: exit 2 ($rc): $(head -c 160 "$tmpd/e")" sh -c "[ $rc = 2 ] && grep -q '$bad.png' '$tmpd/e'"
	ls -l "$tmpd/keep" | md5sum > "$tmpd/after.sum"
	cat "$tmpd"/keep/* | md5sum >> "$tmpd/after.sum"
	check "  ... the maps it would replace unchanged, no staging left" sh -c "cmp -s '$tmpd/keep.sum' '$tmpd/after.sum' &&
		! ls -a '$tmpd' | grep -q staging"
	"$B" maps fit --family "$fam" --albedo "$tmpd/$bad.png" --out "$tmpd/new_$bad" --quiet 2> /dev/null
	check "  ... and a new --out is not made" test ! -e "$tmpd/new_$bad"
done
# A full disk while the maps stream out (strace injects ENOSPC into the K-th
# write of the fit: early, in the first band, and the last write of a good
# run): exit 1 with the system's message, no --out, no staging left.
if command -v strace > /dev/null 2>&1 && strace -f -qq -o /dev/null true 2> /dev/null; then
	# the writes of a good run: the last one is the late failure (one thread:
	# strace counts the writes of each thread apart)
	strace -f -qq -e trace=write -o "$tmpd/writes" "$B" maps fit --family "$fam" --albedo "$tmpd/a.png" \
		--out "$tmpd/good" --threads 1 --quiet
	last=$(grep -c 'write(' "$tmpd/writes")
	echo "# a good fit writes $last times"
	for k in 1 4 "$last"; do
		rm -rf "$tmpd/full"
		strace -f -qq -o /dev/null -e inject=write:error=ENOSPC:when=$k "$B" maps fit --family "$fam" \
			--albedo "$tmpd/a.png" --out "$tmpd/full" --threads 1 --quiet 2> "$tmpd/e"
		rc=$?
		check "fit, disk full at write $k: exit 1 ($rc), '$(head -c 120 "$tmpd/e")', nothing left" sh -c \
			"[ $rc = 1 ] && grep -q 'No space left on device' '$tmpd/e' && [ ! -e '$tmpd/full' ] &&
			! ls -a '$tmpd' | grep -q staging"
	done
else
	skip "strace cannot inject faults here"
fi
tap_done
