#!/bin/sh
# The translucent demo (issue 27, docs/translucency.md): bake `paper`, then the MakeHuman head
# lit only from behind the ear (scenes/human-head-earglow.scene) in POV-Ray, exact mode and
# translucent mode (POV-Ray's subsurface fitted to the bake's Rd(r) under the rest of the table):
#   scripts/demo-translucent.sh [OUT_DIR]     (default out/demo)
# writes OUT_DIR/human-head-earglow-exact.png and OUT_DIR/human-head-earglow.png (translucent) and
# prints the wall time of each step.  SIZE (default 320x240) sets the picture size.  Run after
# scripts/setup.sh (it uses the binary built in this tree); scripts/demo.sh calls it at its end.
set -eu
cd "$(dirname "$0")/.."
B=${SKINBAKE:-./skinbake}
out=${1:-out/demo}
size=${SIZE:-320x240}
scene=scenes/human-head-earglow.scene
py=.venv/bin/python
[ -x "$py" ] || py=python3
model=/usr/share/assimp/models/Collada/human.zae
[ -f "$model" ] || { echo "demo-translucent.sh: $model is missing (scripts/setup.sh installs" \
	"assimp-testmodels)" >&2; exit 1; }
command -v povray >/dev/null || { echo "demo-translucent.sh: povray is missing (scripts/setup.sh" \
	"installs it)" >&2; exit 1; }
mkdir -p "$out"
t0=$(date +%s)
step() { echo "   $(($(date +%s) - t0)) s"; }
echo "== bake (preset paper, 10 incidence nodes, with its radial profile Rd(r))"
$B bake --preset paper --theta-nodes 10 --out "$out/paper-translucent" --quiet
step
for mode in exact translucent; do
	d="$out/human-head-earglow-$mode"
	echo "== $mode: export and render $scene at $size"
	$B export pov --scene "$scene" --bake "$out/paper-translucent" --out "$d" --mode $mode \
		--size "$size" >"$d.log" 2>&1 || { cat "$d.log" >&2; exit 1; }
	# the demo's eyes (scripts/eye_texture.py: hazel irises, white sclerae; scripts/demo.sh)
	if [ -f "$d/human-head-earglow_eyes_texture.png" ]; then
		"$py" scripts/eye_texture.py "$d/human-head-earglow_eyes_texture.png" "$d.eyes.png" &&
			mv "$d.eyes.png" "$d/human-head-earglow_eyes_texture.png"
	fi
	(cd "$d" && povray human-head-earglow.ini >"../$(basename "$d").povray.log" 2>&1) || {
		echo "demo-translucent.sh: povray failed, see $d.povray.log" >&2; exit 1; }
	png="$out/human-head-earglow-$mode.png"
	[ $mode = translucent ] && png="$out/human-head-earglow.png"
	cp "$d/human-head-earglow.png" "$png"
	echo "wrote $png"
	step
done
grep "translucent:" "$out/human-head-earglow-translucent.log" | sed 's/^skinbake export pov: /   /'
echo "demo-translucent.sh: done in $(($(date +%s) - t0)) s"
