#!/bin/sh
# The main job on the default preset: bake `paper`, grow the face texture,
# export the sphere scene for POV-Ray 3.7 and render it to out/demo/sphere.png.
# Run after scripts/setup.sh (it uses the binary built in this tree).
set -eu
cd "$(dirname "$0")/.."
B=${SKINBAKE:-./skinbake}
out=${1:-out/demo}
mkdir -p "$out"
echo "== bake (preset paper, 3 wavelengths, 10 incidence nodes, 5% RMS error)"
$B bake --preset paper --out "$out/paper" --theta-nodes 10 --target-error 0.05 --batch-photons 1000
echo "== texture (face pores and furrows, 512 px, 10 mm tile)"
$B texture --site face --size 512 --tile-mm 10 --out "$out/face" --quiet
echo "== export pov (scenes/sphere.scene)"
$B export pov --bake "$out/paper" --textures "$out/face" --scene scenes/sphere.scene --out "$out/pov"
echo "== render with POV-Ray"
(cd "$out/pov" && povray sphere.ini -D +O../sphere.png) 2> "$out/povray.log" || {
	echo "demo.sh: povray failed, see $out/povray.log" >&2; exit 1; }
echo "wrote $out/sphere.png"
