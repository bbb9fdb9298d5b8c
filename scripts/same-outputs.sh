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
n=0
run simulate --layer d=0.01,n=1.4,mua=2,mus=100,g=0.8 --layer d=inf,n=1.4,mua=1,mus=50,g=0.9 --photons 20000 --theta-in 30 --seed 3 --json
run simulate --layer d=0.01,n=1.4,mua=2,mus=100,g=0.8 --photons 5000 --seed 4
run presets
run preset show paper
run preset show fair-oily
run preset keys
run bake --preset paper --out bake --theta-nodes 4 --resolution 9x6 --target-error 0 --max-photons 400000 --batch-photons 1000 --quiet
run bake --preset fair-oily --out bake2 --wavelengths 450,550,650 --theta-in 30.0,60.0 --resolution 6x4 --target-error 0.2 --batch-photons 500 --quiet
run bake --preset paper --out bakeb --estimator bins --theta-nodes 2 --resolution 6x4 --target-error 0 --max-photons 100000 --batch-photons 1000 --fresnel schlick --quiet
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
find . -type f | LC_ALL=C sort | while read -r f; do
	sed -E 's/"(seconds|photons_per_second|events_per_second)": *[0-9.e+-]*/"\1":X/g; s/[0-9.e+-]+ (s|photons\/s|events\/s)\b/X \1/g; s/\(([0-9.]+) s\)/(X s)/g' "$f" |
	    sha256sum | sed "s|-|$f|"
done
