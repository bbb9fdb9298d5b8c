#!/bin/sh
# The showcase on the default preset (paper): a real head under two lights in
# POV-Ray 3.7.  Bakes what the scene needs (the incidence angles that
# `export pov --plan` lists), grows the face's pores and furrows, exports
# scenes/human-head.scene (the MakeHuman model of Debian's assimp-testmodels,
# 640x480) and scenes/human-pores.scene (its cheek at 0.04 mm per pixel) and
# renders both:  OUT/human-head.png and OUT/human-pores.png  (OUT: out/demo); then the head lit
# from behind in the translucent mode (POV-Ray's subsurface fitted to the bake's Rd(r)):
# OUT/human-head-backlit.png.
# Run after scripts/setup.sh (it uses the binary built in this tree).
set -eu
cd "$(dirname "$0")/.."
B=${SKINBAKE:-./skinbake}
out=${1:-out/demo}
model=/usr/share/assimp/models/Collada/human.zae
[ -f "$model" ] || { echo "demo.sh: $model is missing (scripts/setup.sh installs assimp-testmodels)" >&2; exit 1; }
command -v povray >/dev/null || { echo "demo.sh: povray is missing (scripts/setup.sh installs it)" >&2; exit 1; }
mkdir -p "$out"
t0=$(date +%s)
echo "== plan: what scenes/human-head.scene needs from a bake"
plan=$($B export pov --scene scenes/human-head.scene --plan)
echo "$plan"
# The planned incidence angles: "--theta-nodes N" (curved skin) or "--theta-in A,B".
angles=$(echo "$plan" | sed -n 's/^skin skin: skinbake bake --preset paper \(--theta-[a-z]* [^ ]*\) .*/\1/p')
echo "== bake (preset paper, $angles, 5% RMS error)"
# shellcheck disable=SC2086
$B bake --preset paper $angles --target-error 0.05 --batch-photons 1000 --out "$out/paper" --quiet
echo "== texture (face pores and furrows, 512 px over 10 mm)"
$B texture --site face --size 512 --tile-mm 10 --out "$out/face" --quiet
for s in human-head human-pores; do
	echo "== export and render scenes/$s.scene"
	$B export pov --scene "scenes/$s.scene" --bake "$out/paper" --textures "$out/face" --out "$out/$s" >/dev/null
	(cd "$out/$s" && povray "$s.ini" >povray.log 2>&1) || {
		echo "demo.sh: povray failed, see $out/$s/povray.log" >&2; exit 1; }
	cp "$out/$s/$s.png" "$out/$s.png"
	echo "wrote $out/$s.png"
done
echo "== translucent: scenes/human-head-backlit.scene, lit from behind (docs/translucency.md)"
$B export pov --scene scenes/human-head-backlit.scene --bake "$out/paper" --out "$out/human-head-backlit" \
	--mode translucent --size 320x240 >/dev/null
(cd "$out/human-head-backlit" && povray human-head-backlit.ini >povray.log 2>&1) || {
	echo "demo.sh: povray failed, see $out/human-head-backlit/povray.log" >&2; exit 1; }
cp "$out/human-head-backlit/human-head-backlit.png" "$out/human-head-backlit.png"
echo "wrote $out/human-head-backlit.png"
echo "demo.sh: done in $(($(date +%s) - t0)) s"
