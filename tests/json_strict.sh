#!/bin/sh
# Every JSON the program writes parses with a strict parser (Python's json
# with NaN, Infinity and -Infinity refused): the bake manifests of both
# solvers, a family's family.json, maps.json (new and fitted), the texture
# manifest, the Blender image sets' manifests (a bake and a family), the
# POV-Ray and Mitsuba exports' manifests (Mitsuba's scene.json too),
# scene.json, and the --json outputs of simulate (both solvers), eval and
# verify.  src/io/json.h has the policy (non-finite numbers are null).
# Tiny runs: about 5 s.
. "$top_srcdir/tests/tap.sh"
S=$SKINBAKE
T=$tmpd
# run NAME ARGS...: run skinbake, its stdout to $T/NAME.out; a failure is a test failure.
run() {
	n=$1
	shift
	if "$S" "$@" >"$T/$n.out" 2>"$T/$n.err"; then ok "$n: skinbake $1 ran"; else fail "$n: skinbake $*: $(cat "$T/$n.err")"; fi
}
L="--layer d=0.01,n=1.4,mua=2,mus=100,g=0.8 --layer d=inf,n=1.4,mua=1,mus=50,g=0.9"
run sim_mc simulate $L --photons 2000 --json
run sim_ad simulate $L --solver ad --r-bins 0 --json
run sim_clear simulate --layer d=0.1,mua=0,mus=0 --photons 100 --json
run bake_mc bake --preset paper --wavelengths 470,550 --theta-nodes 2 --resolution 3x3 --target-error 0 \
	--max-photons 16000 --batch-photons 500 --solver mc --out "$T/bmc" --quiet
run bake_ad bake --preset paper --wavelengths 550 --theta-nodes 2 --resolution 3x3 --r-bins 4 \
	--radial-photons 2000 --out "$T/bad" --quiet
run eval eval --bake "$T/bmc" --theta-in 20 --theta-out 35 --phi 40 --json
run eval_ad eval --bake "$T/bad" --theta-in 20 --theta-out 35 --phi 40 --json
run verify verify --bake "$T/bmc" --cells 2 --photons 1000 --json
run family bake --preset paper --wavelengths 550 --theta-nodes 1 --resolution 1x1 --target-error 0 --max-photons 2000 \
	--batch-photons 100 --r-bins 2 --vary dermis.blood=0.01,0.02 --out "$T/fam" --quiet
run maps_new maps new --family "$T/fam" --size 4x4 --out "$T/maps" --quiet
run albedo maps render-albedo --family "$T/fam" --maps "$T/maps" --out "$T/alb.png" --quiet
run maps_fit maps fit --family "$T/fam" --albedo "$T/alb.png" --out "$T/mapsfit" --quiet
run texture texture --size 16 --out "$T/tex" --quiet
run blender export blender --bake "$T/bmc" --textures "$T/tex" --lut-cos 8 --lut-phi 3 --out "$T/blend"
run blender_fam export blender --family "$T/fam" --maps "$T/maps" --lut-cos 8 --lut-phi 3 --out "$T/blendfam"
run scene scene --scene "$top_srcdir/scenes/two-lights.scene" --out "$T/scene.json"
run pov export pov --bake "$T/bmc" --textures "$T/tex" --scene "$top_srcdir/scenes/sphere.scene" \
	--data-dir "$top_srcdir/exporters/pov" --out "$T/pov"
run mitsuba export mitsuba --scene "$top_srcdir/scenes/sphere.scene" --bake "$T/bad" --mode table --out "$T/mts"
# Each --json output and each *.json file the runs wrote, parsed strictly.
for f in sim_mc sim_ad sim_clear eval eval_ad verify; do
	[ -s "$T/$f.out" ] && cp "$T/$f.out" "$T/stdout_$f.json"
done
n=0
for f in $(find "$T" -name '*.json' | LC_ALL=C sort); do
	n=$((n + 1))
	rel=${f#"$T"/}
	if python3 -c 'import json, sys
def refuse(c):
    raise ValueError("%s is not JSON" % c)
json.load(open(sys.argv[1]), parse_constant=refuse)' "$f" 2>"$T/why"; then
		ok "$rel parses strictly"
	else
		fail "$rel: $(tail -n 1 "$T/why")"
	fi
done
# The list above is not empty by accident: each kind was written.
for k in bmc/manifest.json bad/manifest.json fam/family.json maps/maps.json mapsfit/maps.json tex/manifest.json \
	blend/manifest.json blendfam/manifest.json pov/manifest.json mts/manifest.json mts/scene.json scene.json \
	stdout_verify.json; do
	check "$k was written" test -s "$T/$k"
done
tap_done
