#!/bin/sh
# skinbake texture: help, sites, output contract, determinism, preset files,
# bad input (exit 2, no files), and (with python3) normals against finite
# differences of the written 16-bit height map plus seamless wrap-around.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
S=$SKINBAKE

# --help names every parameter that --dump-config prints.
"$S" texture --help >"$tmpd/help" 2>&1
keys=$("$S" texture --dump-config | sed -n 's/^\([a-z_]*\) = .*/\1/p' | grep -v '^site$' | tr _ -)
missing=
for k in $keys; do grep -q -- "--$k " "$tmpd/help" || missing="$missing $k"; done
check "--help lists every parameter (missing:$missing)" test -z "$missing" -a -n "$keys"
for o in --site --preset-file --out --list-sites --dump-config; do
	check "--help lists $o" grep -q -- "$o" "$tmpd/help"
done

sites=$("$S" texture --list-sites | awk '{print $1}')
for s in face cheek forehead nose hand forearm back; do
	check "--list-sites has $s" sh -c "echo '$sites' | grep -qx $s"
done

# Every site writes the full set of files at a small size.
for s in $sites; do
	od="$tmpd/$s"
	if "$S" texture --site "$s" --size 96 --quiet --out "$od"; then ok "site $s runs"; else fail "site $s runs"; fi
	all=1
	for f in height.png normal.png normal.exr height.exr preview.png pores_height.png furrows_height.png \
		roughness_far.png cavity.png manifest.json; do
		test -s "$od/$f" || all=0
	done
	check "site $s: all files" test $all = 1
	check "site $s: no temporary files left" sh -c "! ls '$od' | grep -q tmp"
	check "site $s: manifest site and convention" sh -c \
	    "grep -q '\"site\":\"$s\"' '$od/manifest.json' && grep -q '\"normal_convention\":\"OpenGL +Y\"' '$od/manifest.json'"
	for k in skinbake:tile_mm skinbake:height_min_um skinbake:height_max_um skinbake:site skinbake:seed Software; do
		grep -a -q "$k" "$od/height.png" || all=0
	done
	check "site $s: height.png tEXt keys" test $all = 1
done
check "manifest lists files and version" sh -c "grep -q '\"files\"' '$tmpd/hand/manifest.json' && grep -q '\"skinbake_version\"' '$tmpd/hand/manifest.json'"

# Determinism for a seed; another seed differs.
"$S" texture --site hand --size 128 --seed 7 --quiet --out "$tmpd/a"
"$S" texture --site hand --size 128 --seed 7 --quiet --out "$tmpd/b"
"$S" texture --site hand --size 128 --seed 8 --quiet --out "$tmpd/c"
check "same seed, same height.png" cmp -s "$tmpd/a/height.png" "$tmpd/b/height.png"
check "same seed, same normal.exr" cmp -s "$tmpd/a/normal.exr" "$tmpd/b/normal.exr"
check "same seed, same manifest" cmp -s "$tmpd/a/manifest.json" "$tmpd/b/manifest.json"
check "other seed, other height.png" sh -c "! cmp -s '$tmpd/a/height.png' '$tmpd/c/height.png'"

# Preset file: [texture] with site first, overrides, other sections ignored.
cat >"$tmpd/p.ini" <<EOF
[skin]
melanin = 0.1
[texture]
levels = 1
site = forearm
furrow_depth = 22.5
EOF
"$S" texture --preset-file "$tmpd/p.ini" --stretch 2 --dump-config >"$tmpd/dump" 2>&1
check "preset: site applies" grep -qx "site = forearm" "$tmpd/dump"
check "preset: keys override the site" sh -c "grep -qx 'levels = 1' '$tmpd/dump' && grep -qx 'furrow_depth = 22.5' '$tmpd/dump'"
check "preset: options override the file" grep -qx "stretch = 2" "$tmpd/dump"
"$S" texture --dump-config --site hand >"$tmpd/hand.ini"
"$S" texture --preset-file "$tmpd/hand.ini" --dump-config >"$tmpd/hand2.ini"
check "dump-config round-trips" cmp -s "$tmpd/hand.ini" "$tmpd/hand2.ini"

# Bad input: exit 2, a message naming the option, and nothing written.
bad() {	# DESC PATTERN ARGS...: texture ARGS refused (tests/lib/refused.sh)
	b_d=$1 b_p=$2
	shift 2
	refused "bad input: $b_d" "$b_p" "$tmpd/bad" "$S" texture "$@" --out "$tmpd/bad"
}
bad "size too small" "--size = 3 is out of range" --size 3
bad "negative pore depth" "--pore-depth" --pore-depth -5
bad "not a number" "--stretch = 'abc' is not a decimal number in \[1, 10\]" --stretch abc
bad "unknown site" "unknown site 'elbow'" --site elbow
bad "too many levels" "--levels" --levels 9
bad "fractional levels" "whole number" --levels 1.5
bad "cell larger than half the tile" "furrow cell" --furrow-cell 8 --tile-mm 10
bad "too many junctions" "junctions" --furrow-cell 0.02 --tile-mm 100
bad "unknown option" "unknown option" --frobnicate 1
bad "missing preset file" "nope.ini': No such file or directory" --preset-file "$tmpd/nope.ini"
printf '[texture]\nsize = 20\nwibble = 3\n' >"$tmpd/badkey.ini"
bad "unknown preset key, with line" "badkey.ini:3: unknown key 'wibble'" --preset-file "$tmpd/badkey.ini"
printf '[texture]\nsite = hand\n; %s\n' "$(printf '%0250d' 0)" > "$tmpd/long.ini"
bad "over-long line is an error, not a silent split" "long.ini:3: line 3 is longer than 199" --preset-file "$tmpd/long.ini"
printf '[texture]\npore_density = 500\n' >"$tmpd/badval.ini"
bad "preset value out of range" "badval.ini:2: pore_density = 500 is out of range" --preset-file "$tmpd/badval.ini"
"$S" texture --size 64 >"$tmpd/err" 2>&1
check "missing --out is a usage error" test $? -eq 2

# Pixel-level checks of the written files (need only python3's zlib).
if command -v python3 >/dev/null 2>&1; then
	python3 - "$tmpd/hand" "$tmpd/face" >"$tmpd/py" 2>&1 <<'EOF'
import math, os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
import images

def read_png(path):
    w, h, ch, bits, rows, text = images.read_png(path)
    return w, h, ch, tuple(v for row in rows for px in row for v in px), text

bad = 0
for d in sys.argv[1:]:
    w, h, ch, H, t = read_png(d + '/height.png')
    lo, hi, tile = float(t['skinbake:height_min_um']), float(t['skinbake:height_max_um']), float(t['skinbake:tile_mm'])
    hv = [lo + v / 65535.0 * (hi - lo) for v in H]
    w2, h2, ch2, N, _ = read_png(d + '/normal.png')
    pitch = tile * 1000.0 / w
    worst = 0.0
    for r in range(h):
        for c in range(w):
            hx = (hv[r * w + (c + 1) % w] - hv[r * w + (c - 1) % w]) / (2 * pitch)
            hy = (hv[((r - 1) % h) * w + c] - hv[((r + 1) % h) * w + c]) / (2 * pitch)
            nrm = math.sqrt(hx * hx + hy * hy + 1)
            e = [-hx / nrm, -hy / nrm, 1 / nrm]
            got = [N[3 * (r * w + c) + k] / 65535.0 * 2 - 1 for k in range(3)]
            worst = max(worst, max(abs(e[k] - got[k]) for k in range(3)))
    print('%s: normals vs finite differences of height.png: worst %.2e' % (d, worst))
    if worst > 2e-3: bad += 1
    # Wrap-around differences are distributed like interior ones.
    def rms_col(c):
        return math.sqrt(sum((hv[r * w + (c + 1) % w] - hv[r * w + c]) ** 2 for r in range(h)) / h)
    # (One column of ~100 samples: its rank among the interior columns is
    # uniform, so test against the spread rather than the extremes.)
    inner = sorted(rms_col(c) for c in range(w - 1)); seam = rms_col(w - 1)
    med = inner[len(inner) // 2]
    print('%s: wrap column rms %.3g, interior median %.3g (%.3g..%.3g)' % (d, seam, med, inner[0], inner[-1]))
    if not (0.5 * med <= seam <= 2 * med): bad += 1
sys.exit(1 if bad else 0)
EOF
	rc=$?
	sed 's/^/# /' "$tmpd/py"
	check "normal.png agrees with finite differences of height.png; seamless" test $rc -eq 0
else
	skip "python3 not found: pixel checks of the PNG files"
fi
tap_done
