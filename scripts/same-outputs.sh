#!/bin/sh
# Refactoring check: run one fixed set of commands with a skinbake binary and
# print a checksum per output file, with wall times masked.  Run it with the
# binary before and after a change; identical listings mean byte-identical
# outputs.   usage: scripts/same-outputs.sh SKINBAKE WORKDIR > sums.txt
set -eu
B=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
top=$(cd "$(dirname "$0")/.." && pwd)
W=$2
rm -rf "$W"; mkdir -p "$W"; cd "$W"
run() { echo "\$ $*" > "cmd.$n.txt"; "$B" "$@" > "out.$n.txt" 2> "err.$n.txt" || echo "exit $?" >> "out.$n.txt"; n=$((n + 1)); }
# Monte Carlo bakes: `bake ... --solver mc` where the binary has the option
# (its default is adding-doubling since issue 13), listed without it, so that
# binaries from before and after compare; their manifests are compared with
# the keys added since then left out (norm_manifest below).
MC=
if "$B" bake --help 2>/dev/null | grep -q -- '--solver'; then MC="--solver mc"; fi
runmc() { echo "\$ $*" > "cmd.$n.txt"; "$B" "$@" $MC > "out.$n.txt" 2> "err.$n.txt" || echo "exit $?" >> "out.$n.txt"; n=$((n + 1)); }
n=0
run simulate --layer d=0.01,n=1.4,mua=2,mus=100,g=0.8 --layer d=inf,n=1.4,mua=1,mus=50,g=0.9 --photons 20000 --theta-in 30 --seed 3 --json
run simulate --layer d=0.01,n=1.4,mua=2,mus=100,g=0.8 --photons 5000 --seed 4
run presets
run preset show paper
run preset show fair-oily
run preset keys
runmc bake --preset paper --out bake --theta-nodes 4 --resolution 9x6 --target-error 0 --max-photons 400000 --batch-photons 1000 --quiet
runmc bake --preset fair-oily --out bake2 --wavelengths 450,550,650 --theta-in 30.0,60.0 --resolution 6x4 --target-error 0.2 --batch-photons 500 --quiet
runmc bake --preset paper --out bakeb --estimator bins --theta-nodes 2 --resolution 6x4 --target-error 0 --max-photons 100000 --batch-photons 1000 --fresnel schlick --quiet
run eval --bake bake --theta-in 20 --theta-out 35 --phi 40
run eval --bake bake --theta-in 20 --theta-out 35 --phi 40 --json
run texture --site face --size 128 --out tex --quiet
run texture --site hand --size 96 --seed 7 --out tex2 --quiet
run export pov --bake bake --textures tex --scene "$top/scenes/sphere.scene" --out pov1 --data-dir "$top/exporters/pov"
run export pov --bake bake --textures tex --scene "$top/scenes/two-lights.scene" --out pov2 --data-dir "$top/exporters/pov"
run export pov --bake bake --textures tex2 --scene "$top/scenes/hand.scene" --out pov3 --data-dir "$top/exporters/pov"
run export pov --bake bake --light position=3:4:-5 --light type=point,position=-3:2:-4 --camera type=perspective,location=0:0:-5 --out pov4 --data-dir "$top/exporters/pov"
run export blender --bake bake --textures tex --out blend
run bake --preset nope --out x
run simulate --layer d=-1
# More options of simulate, bake, eval, texture and export blender.
run simulate --layer d=0.02,n=1.5,mua=0,mus=0 --layer d=0.05,n=1.4,mua=5,mus=200,g=0.85 --layer d=inf,n=1.37,mua=1,mus=80,g=0.8 --n-above 1.33 --n-below 1.5 --theta-in 55 --photons 8000 --seed 9 --threads 1 --batches 7 --fresnel schlick --theta-out-step 10 --phi-step 30 --r-step 0.01 --r-bins 20 --roulette-w 0.1 --roulette-chance 0.5 --max-steps 100000 --json
run simulate --layer d=0.05,mua=3,mus=90,g=0.7 --photons 3000 --r-bins 0 --theta-out-step 15 --phi-step 45 --json
printf '[skin]\nbase = fair-oily\nname = mine\n[dermis]\nblood = 0.05\n' > mine.ini
runmc bake --preset-file mine.ini --out bake3 --spectral 500:600:50 --theta-nodes 3 --resolution 4x3 --target-error 0 --max-photons 72000 --batch-photons 1000 --r-step 0.01 --r-bins 10 --seed 5 --threads 1 --quiet
run eval --bake bake2 --theta-in 45 --theta-out 10 --phi 250 --json
run eval --bake bakeb --theta-in 0 --theta-out 89 --phi 180
run texture --site forearm --size 64 --levels 1 --stretch 2 --seed 3 --out tex3 --quiet
run texture --site back --dump-config
run export blender --bake bake3 --textures tex3 --sun-elevation 30 --sun-azimuth 20 --view-elevation 70 --lut-cos 16 --lut-phi 5 --map-size 4 --out blend2
run export blender --bake bakeb --out blend3 --lut-cos 8 --lut-phi 3
run export blender --bake nope --out blend4
run texture --size 16 --out tex4
# Adding-doubling (issue 13): a bake, eval on it, simulate (new outputs; a
# binary from before lists these as errors).
run bake --preset paper --out bakead --theta-nodes 3 --resolution 9x6 --r-bins 50 --radial-photons 4000 --quiet
run eval --bake bakead --theta-in 20 --theta-out 35 --phi 40 --json
run simulate --solver ad --layer d=0.01,n=1.4,mua=2,mus=100,g=0.8 --layer d=inf,n=1.4,mua=1,mus=50,g=0.9 --theta-in 30 --r-bins 0 --json
# Texture with every parameter (issue 11 items 5-6: cmd_texture, relief and
# the Delaunay furrows split), a preset file, an output path that is not a directory,
# a range error and a junction count over the limit.
run texture --size 80 --seed 11 --tile-mm 6 --pore-density 3 --pore-radius 40 --pore-radius-sd 0.3 --pore-depth 50 --pore-depth-sd 0.2 --pore-aspect 1.5 --pore-junction 0.4 --pore-regularity 0.5 --levels 3 --furrow-cell 1.2 --furrow-width 60 --furrow-depth 40 --furrow-depth-sd 0.3 --ridge-height 8 --level-scale 0.45 --level-gain 0.6 --stretch 3 --orientation 25 --furrow-regularity 0.4 --out tex5
printf '[texture]\nlevels = 2\nsite = cheek\nstretch = 1.5\n' > tex.ini
run texture --preset-file tex.ini --size 48 --seed 2 --out tex6
run texture --preset-file tex.ini --dump-config
printf 'x' > notadir
run texture --size 16 --out notadir/sub
run texture --furrow-cell 40 --tile-mm 10 --out tex7
run texture --levels 2 --furrow-cell 0.02 --tile-mm 500 --out tex8
# A manifest without the keys added by issue 13 (solver record, per-job
# method, batches and resolution, radial error, method and target, pilot
# photons) and without the --solver mc added above.
norm_manifest() {
	python3 -c 'import collections, json, sys
m = json.load(open(sys.argv[1]), object_pairs_hook=collections.OrderedDict)
m.pop("solver", None)
if "command" in m: m["command"] = m["command"].replace(" --solver mc", "")
for j in m.get("jobs", []):
    for k in ("solver", "batches", "n_quad", "fourier_orders"): j.pop(k, None)
for k in ("mean_radius_err_cm", "method", "photons", "seconds", "target_rel_err"): m.get("radial", {}).pop(k, None)
m.get("result", {}).pop("pilot_photons", None)
print(json.dumps(m, indent=1))' "$1"
}
find . -type f | LC_ALL=C sort | while read -r f; do
	case "$f" in */manifest.json) norm_manifest "$f" ;; *) cat "$f" ;; esac |
	sed -E 's/"(seconds|photons_per_second|events_per_second)": *[0-9.e+-]*/"\1":X/g; s/[0-9.e+-]+ (s|photons\/s|events\/s)\b/X \1/g; s/\(([0-9.]+) s\)/(X s)/g' |
	    sha256sum | sed "s|-|$f|"
done
