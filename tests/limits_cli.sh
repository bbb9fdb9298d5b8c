#!/bin/sh
# Limits said before work and write errors said with their cause (issue 23
# items 5 and 6): seeds exact over [0, 2^64-1]; a bake too large for the
# memory refused at once with the numbers and the options that lower them;
# a full disk (ENOSPC injected by strace) and a full standard output
# (/dev/full) end with exit status 1, the errno text and no output; a
# non-UTF-8 --out makes a manifest strict JSON readers take; a light at the
# camera's target point, a mesh with an infinite vertex, a directory given
# as a mesh and an unclosed [section are refused naming the real cause.
# Costs about 10 s.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
cd "$tmpd" || exit 1
BK="--preset paper --solver ad --theta-nodes 3 --resolution 9x6 --radial-error 0.2 --r-bins 20 --quiet"
MC="--preset paper --solver mc --theta-nodes 1 --resolution 3x3 --r-bins 10 --max-photons 1e5 --target-error 0 \
--batch-photons 1000 --quiet"
"$B" bake $BK --out bk || fail "good bake"

# bad DESC PATTERN CMD...: exit 2 and stderr matches PATTERN (grep -E; tests/lib/refused.sh)
. "$top_srcdir/tests/lib/refused.sh"
refused_ere=1
bad() {
	b_d=$1 b_p=$2
	shift 2
	refused "$b_d" "$b_p" "" "$@"
}
json() { python3 -c "import json,sys; m=json.load(open(sys.argv[1], encoding='utf-8')); print($2)" "$1"; }

# ---- seeds
check "bake --seed 9.2e18 (once refused) is taken exactly" sh -c \
	"'$B' bake $MC --seed 9.2e18 --out s1 && [ \"\$(python3 -c \"import json; print(json.load(open('s1/manifest.json'))['settings']['seed'])\")\" = 9200000000000000000 ]"
check "bake --seed 2^64-1 is taken exactly" sh -c \
	"'$B' bake $MC --seed 18446744073709551615 --out s2 && [ \"\$(python3 -c \"import json; print(json.load(open('s2/manifest.json'))['settings']['seed'])\")\" = 18446744073709551615 ]"
bad "bake --seed 2^64 is out of range" "--seed = 18446744073709551616 is out of range \[0, 2\^64-1\]" \
	"$B" bake $MC --seed 18446744073709551616 --out s3
bad "bake --seed -1 is out of range" "--seed = -1 is out of range" "$B" bake $MC --seed -1 --out s3
"$B" texture --size 16 --seed 9007199254740992 --out t0 --quiet && "$B" texture --size 16 --seed 9007199254740993 --out t1 --quiet
check "texture --seed 2^53+1 is not rounded to 2^53: manifest exact, other maps" sh -c \
	"[ \"\$(python3 -c \"import json; print(json.load(open('t1/manifest.json'))['seed'])\")\" = 9007199254740993 ] && ! cmp -s t0/height.png t1/height.png"

# ---- memory said before work
avail=$(awk '/^MemAvailable/ { print $2 }' /proc/meminfo)
if [ -n "$avail" ] && [ "$avail" -lt 50000000 ]; then
	bad "a bake far larger than the memory is refused at once, with the numbers" \
		"needs about [0-9.]+ GB of memory \(estimated\), [0-9.]+ GB are available; lower --resolution" \
		timeout 20 "$B" bake --preset fair-oily --solver ad --spectral 400:780:4 --theta-nodes 90 --resolution 360x360 \
		--out huge --quiet
	check "... and leaves nothing" [ ! -e huge ]
else
	skip "more than 50 GB of memory available: the large bake would fit"
fi

# ---- write errors
check "a full standard output is exit 1 with its cause" sh -c \
	"'$B' preset show paper --ini > /dev/full 2> err.txt; [ \$? -eq 1 ] && grep -q 'No space left on device' err.txt"
if command -v strace > /dev/null 2>&1 && strace -f -qq -o /dev/null true 2> /dev/null; then
	# nospace DESC CALL K CMD...: CMD with its K-th CALL failing ENOSPC (single-threaded
	# writers for write: a parallel one may meet the failure in its own message)
	nospace() {
		desc=$1 call=$2 k=$3
		shift 3
		ASAN_OPTIONS=detect_leaks=0 strace -f -qq -o /dev/null -e inject=$call:error=ENOSPC:when=$k "$@" --out full \
			> /dev/null 2> err.txt
		rc=$?
		left=$(ls -A | grep -c '^\.\?full')
		if [ $rc -eq 1 ] && grep -q "No space left on device" err.txt && [ "$left" -eq 0 ]; then
			ok "$desc: exit 1, the cause said, no file left"
		else
			fail "$desc (exit $rc, $left left): $(head -c 300 err.txt)"
		fi
	}
	nospace "texture, disk full in an EXR" pwrite64 3 "$B" texture --size 16 --quiet
	nospace "export blender, disk full in a PNG" write 2 "$B" export blender --bake bk --lut-cos 8 --lut-phi 3 --mode exact
	nospace "bake, disk full in an EXR" pwrite64 5 "$B" bake $BK
	nospace "bake, disk full in manifest.json" write 2 "$B" bake $BK
else
	skip "strace cannot inject faults here"
fi

# ---- names that are not UTF-8
weird=$(printf 'out\377\376')
cat > utf8.py <<'EOF'
import json, os, sys
m = json.load(open(os.fsencode(sys.argv[1]) + b"/manifest.json", encoding="utf-8"))
assert "\\xFF\\xFE" in m["command"], m["command"]
EOF
check "bake --out a non-UTF-8 name: the manifest is strict JSON with the bytes as \\xHH" sh -c \
	"'$B' bake $BK --out \"\$1\" && python3 utf8.py \"\$1\"" sh "$weird"
check "... and the bake reads back" sh -c "'$B' eval --bake \"\$1\" --theta-in 10 --theta-out 10 --phi 0 > /dev/null" sh "$weird"

# ---- messages that name the real cause
bad "export pov: a parallel light at its target point (the default 0:0:0)" \
	"--light L1: position 0:0:0 and point_at coincide" "$B" export pov --bake bk \
	--light type=parallel,position=0:0:0 --camera type=orthographic,location=0:0:-10 --out pv
scene() {
	printf '[scene]\nwidth = 16\nheight = 16\nunit_mm = 4\n[camera]\ntype = orthographic\n'
	printf 'location = 0 0 -10\nlook_at = 0 0 0\nwidth = 2\n[light key]\ntype = parallel\nposition = 1 3 -4\n'
	printf '[skin skin]\npreset = paper\n[object thing]\nshape = mesh\nfile = %s\n' "$1"
}
printf 'v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n' > inf.obj
scene "$tmpd/inf.obj" > inf.scene
bad "a mesh vertex of 1e39 (inf as a float)" "inf.obj: vertex [0-9]+ has x = inf; mesh coordinates must be finite" \
	"$B" export pov --bake bk --scene inf.scene --out pv
mkdir adir.obj
scene "$tmpd/adir.obj" > dir.scene
bad "a directory given as the mesh file" "adir.obj is a directory, not a model file" \
	"$B" export pov --bake bk --scene dir.scene --out pv
"$B" preset show refstack --ini | sed 's/^\[dermis\]$/[dermis/' > open.ini
bad "a section header without ']'" "open.ini:[0-9]+: the section header '\[dermis' is not closed" \
	"$B" bake --preset-file open.ini --out o --solver ad --theta-nodes 1 --resolution 3x3 --quiet
tap_done
