#!/bin/sh
# The MakeHuman head from Debian's assimp-testmodels in Blender, skinned by import_skin.py in
# exact mode under two lamps (a key sun and a fill point lamp), rendered with Cycles CPU.
#   scripts/render-blender-head.sh [OUT_DIR]       (default out/blender-head)
# Environment: PRESET (default paper), SAMPLES (default 32), SIZE (default 640x480),
# MODEL (default /usr/share/assimp/models/Collada/human.zae).  Writes OUT_DIR/head.png (the head)
# and OUT_DIR/cheek.png (a close-up of the left cheek, where the pores are a few pixels wide),
# and the .blend files they were rendered from.  Run after scripts/setup.sh.
set -eu
cd "$(dirname "$0")/.."
S=${SKINBAKE:-./skinbake}
out=${1:-out/blender-head}
preset=${PRESET:-paper}
samples=${SAMPLES:-32}
size=${SIZE:-640x480}
model=${MODEL:-/usr/share/assimp/models/Collada/human.zae}
imp=exporters/blender/import_skin.py
BL() { blender -b -noaudio --python-exit-code 1 "$@"; }
[ -f "$model" ] || { echo "render-blender-head.sh: $model is missing (apt-get install assimp-testmodels)" >&2; exit 1; }
mkdir -p "$out"
t0=$(date +%s)
if [ ! -f "$out/bake/manifest.json" ]; then
	echo "== bake ($preset, 10 incidence nodes, 5% RMS error)"
	$S bake --preset "$preset" --out "$out/bake" --theta-nodes 10 --target-error 0.05 --batch-photons 1000 --quiet
fi
echo "== texture (face: pores and furrows, 1024 px over 8 mm)"
$S texture --site face --size 1024 --out "$out/face" --quiet
echo "== export blender"
$S export blender --bake "$out/bake" --textures "$out/face" --out "$out/skin"
for shot in head cheek; do
	echo "== $shot: scene, import (exact mode, two lamps), render ($size, $samples samples)"
	BL --factory-startup --python exporters/blender/human_scene.py -- "$out/$shot-scene.blend" \
		--model "$model" --shot $shot --size "$size" --samples "$samples" >"$out/$shot-scene.log" 2>&1 ||
		{ echo "render-blender-head.sh: see $out/$shot-scene.log" >&2; exit 1; }
	# --uv-size: the face's UV density, sqrt(surface / UV area) over the body mesh's faces above
	# 1.45 m and in front (0.964 m per UV unit); the whole body measures 1.607, its head gets
	# more UV space, and the importer warns that the density varies.
	BL "$out/$shot-scene.blend" --python "$imp" -- "$out/skin" --objects human-base --mode exact \
		--uv-size 0.964 --save "$out/$shot.blend" >"$out/$shot-import.log" 2>&1 ||
		{ echo "render-blender-head.sh: see $out/$shot-import.log" >&2; exit 1; }
	grep "^import_skin.py" "$out/$shot-import.log"
	t1=$(date +%s)
	BL "$out/$shot.blend" -o "//$shot-render_" -f 1 >"$out/$shot-render.log" 2>&1 ||
		{ echo "render-blender-head.sh: see $out/$shot-render.log" >&2; exit 1; }
	mv "$out/$shot-render_0001.png" "$out/$shot.png"
	echo "wrote $out/$shot.png (render $(( $(date +%s) - t1 )) s)"
done
echo "total $(( $(date +%s) - t0 )) s"
