#!/bin/sh
# Meshes in the POV-Ray exporter, rendered by the real POV-Ray (tiny,
# 16-bit linear): every model format loads and renders; bump maps on a mesh
# follow its UVs with no seam; the MakeHuman head with two lights against
# the sum of single-light renders (auto's choice: passes as light layers for
# point lights and a perspective camera, the mixture table for distant
# lights and an orthographic one); bad models, unknown formats, meshes
# without UVs and missing mesh names give a clear message, exit 2 and no
# output; --size and --unit-mm.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"

CMP="$top_builddir/tests/pov_compare"
TD="$top_srcdir/tests/data/mesh"
HUMAN=/usr/share/assimp/models/Collada/human.zae

. "$top_srcdir/tests/lib/pov.sh"
pov_require

# export OUT [options]: skinbake export pov --mode exact (the mode these checks are about;
# the default auto is translucent on meshes), output in $tmpd/OUT
export_pov() {
	e_out=$1
	shift
	"$SKINBAKE" export pov --mode exact --out "$tmpd/$e_out" "$@" >"$tmpd/$e_out.stdout" 2>"$tmpd/$e_out.stderr"
}

# scene NAME OBJECT-LINES...: a scene file $tmpd/NAME.scene with an
# orthographic camera on the unit square, one parallel light, skin 'skin'.
scene() {
	s_n=$1
	shift
	{
		printf '[scene]\nwidth = 64\nheight = 64\nunit_mm = 4\n[camera]\ntype = orthographic\n'
		printf 'location = 0 0 -10\nlook_at = 0 0 0\nwidth = 2\n'
		printf '[light key]\ntype = parallel\nposition = 1000 300 -400\ncolor = 0.8 0.8 0.8\n'
		printf '[skin skin]\npreset = paper\nsite = face\n[object thing]\n'
		for l in "$@"; do printf '%s\n' "$l"; done
	} >"$tmpd/$s_n.scene"
}

B="$tmpd/bake"
if "$SKINBAKE" bake --preset paper --out "$B" --theta-nodes 4 --resolution 9x9 --estimator bins \
	--max-photons 1e6 --batch-photons 4000 --target-error 0 --quiet >"$tmpd/bake.log" 2>&1; then
	ok "small bake of preset paper"
else
	fail "small bake of preset paper: $(tail -3 "$tmpd/bake.log")"
	tap_done
	exit 1
fi
TX="$tmpd/tex"
"$SKINBAKE" texture --site face --size 64 --tile-mm 4 --out "$TX" --quiet >"$tmpd/tex.log" 2>&1 ||
	"$CMP" mkheight --out "$TX" --kind sine

# 1. Every format: the unit square facing the camera loads, exports with
#    UVs and normals, and renders lit.
for f in square.obj square.ply square.gltf square.dae; do
	n=$(echo "$f" | tr . -)
	scene "$n" "shape = mesh" "file = $TD/$f" "translate = -0.5 -0.5 0"
	if export_pov "$n" --scene "$tmpd/$n.scene" --bake "$B" && pov_render "$tmpd/$n" "$n" 32 32; then
		grep -q "uv_vectors { 4" "$tmpd/$n/${n}_mesh_thing.inc" && grep -q "normal_vectors { 4" "$tmpd/$n/${n}_mesh_thing.inc"
		check "$f: mesh2 with normals and UVs, rendered" test $? -eq 0
	else
		fail "$f: $(cat "$tmpd/$n.stderr")"
	fi
done

# 2. Bump maps follow the UVs: a 32-triangle grid whose UVs run along x and
#    y renders as the flat patch with the same map, and with its UVs turned
#    a quarter as the patch turned a quarter (any seam at a triangle edge, or
#    a bump frame not following the UVs, would differ); the turned grid
#    differs from the unturned patch (negative control).
scene patch "shape = patch" "size = 4 4 1"
scene patch90 "shape = patch" "size = 4 4 1" "rotate = 0 0 90"
scene grid "shape = mesh" "file = $TD/grid.obj"
scene grid90 "shape = mesh" "file = $TD/grid-turned.obj"
for n in patch patch90 grid grid90; do
	export_pov "$n" --scene "$tmpd/$n.scene" --bake "$B" --textures "$TX" --bump-filter off &&
		pov_render "$tmpd/$n" "$n" 96 96 || fail "bump scene $n: $(cat "$tmpd/$n.stderr")"
done
r=$("$CMP" sum --render "$tmpd/grid/r.png" --parts "$tmpd/patch/r.png" --tol 0.005)
check "bump-mapped grid mesh = bump-mapped patch: $r (<= 0.5 %)" test $? -eq 0
r=$("$CMP" sum --render "$tmpd/grid90/r.png" --parts "$tmpd/patch90/r.png" --tol 0.005)
check "grid with UVs turned a quarter = patch turned a quarter: $r (<= 0.5 %)" test $? -eq 0
r=$("$CMP" differ --render "$tmpd/grid90/r.png" --other "$tmpd/patch/r.png" --min 0.02)
check "negative control: the turned UVs change the shading: $r" test $? -eq 0
r=$("$CMP" seam --render "$tmpd/grid/r.png" --column 48 --max 2)
check "no seam at the grid's middle (a triangle edge and a tile boundary): $r" test $? -eq 0

# 3. The MakeHuman head with two lights: the default strategy against the
#    sum of single-light renders (each light alone, with its own table).
if [ -r "$HUMAN" ]; then
	cat >"$tmpd/human.scene" <<EOF
[scene]
width = 96
height = 72
unit_mm = 1
[camera]
type = perspective
location = 200 1580 -620
look_at = 0 1545 -90
angle = 30
[light key]
type = point
position = -900 2300 -1400
color = 1 1 1
[light fill]
type = point
position = 1400 1500 -800
color = 0.35 0.35 0.38
[skin skin]
preset = paper
site = face
[object head]
shape = mesh
file = $HUMAN
mesh = human-baseMesh
scale = 1000
EOF
	sed '/^\[light fill\]/,/^color/d' "$tmpd/human.scene" >"$tmpd/human-key.scene"
	sed '/^\[light key\]/,/^color/d' "$tmpd/human.scene" >"$tmpd/human-fill.scene"
	# Distant lights and an orthographic camera: the mixture is exact.
	sed 's/^type = point/type = parallel/; s/^type = perspective/type = orthographic\nwidth = 320/; /^angle/d' \
		"$tmpd/human.scene" >"$tmpd/humanp.scene"
	sed '/^\[light fill\]/,/^color/d' "$tmpd/humanp.scene" >"$tmpd/humanp-key.scene"
	sed '/^\[light key\]/,/^color/d' "$tmpd/humanp.scene" >"$tmpd/humanp-fill.scene"
	# No bump map here: relief finer than these 3.5 mm pixels is aliasing
	# noise that the inset layers sample a hair apart (the grid tests bumps).
	for n in human human-key human-fill humanp humanp-key humanp-fill; do
		export_pov "$n" --scene "$tmpd/$n.scene" --bake "$B" && pov_render "$tmpd/$n" "$n" 96 72 ||
			fail "human scene $n: $(cat "$tmpd/$n.stderr")"
	done
	# --bump-filter off: the bump map stays where the relief is below a pixel (else the
	# far roughness of docs/relief.md replaces it).
	export_pov humant --scene "$tmpd/human.scene" --bake "$B" --textures "$TX" --bump-filter off
	grep -q "so passes" "$tmpd/human.stderr"
	check "point lights, perspective camera: auto estimates the mixture too far off and renders passes ($(grep -o 'would be [0-9.]* %' "$tmpd/human.stderr"))" test $? -eq 0
	r=$("$CMP" sum --render "$tmpd/human/r.png" --parts "$tmpd/human-key/r.png" "$tmpd/human-fill/r.png" --tol 0.01 --interior)
	check "MakeHuman head, two point lights, perspective, default strategy vs sum of single-light renders, skin pixels off silhouettes and shadow edges: $r (<= 1 %)" test $? -eq 0
	grep -q "so mixture" "$tmpd/humanp.stderr"
	check "parallel lights, orthographic camera: auto picks the mixture table" test $? -eq 0
	r=$("$CMP" sum --render "$tmpd/humanp/r.png" --parts "$tmpd/humanp-key/r.png" "$tmpd/humanp-fill/r.png" --tol 0.01 --interior)
	check "MakeHuman head, two parallel lights, orthographic, default strategy (mixture) vs sum, same pixels: $r (<= 1 %)" test $? -eq 0
	grep -q "texture_list" "$tmpd/humant/human_mesh_head.inc"
	check "the head's visible triangles carry their own bump maps" test $? -eq 0
else
	skip "MakeHuman model absent ($HUMAN: scripts/setup.sh installs assimp-testmodels)"
fi

# 4. Bad models: a clear message, exit 2, no output.
bad() {	# NAME PATTERN OBJECT-LINES...: that scene's export refused (tests/lib/refused.sh)
	b_n=$1 b_pat=$2
	shift 2
	scene "$b_n" "$@"
	refused "$b_n: exit 2, message, no output" "$b_pat" "$tmpd/$b_n" "$SKINBAKE" export pov \
		--out "$tmpd/$b_n" --scene "$tmpd/$b_n.scene" --bake "$B" --textures "$TX"
	echo "# $refused_msg"
}
bad broken "broken.gltf: not a model libassimp can read" "shape = mesh" "file = $TD/broken.gltf"
bad unknown "unknown model format '.xyz' (libassimp reads .*obj" "shape = mesh" "file = $TD/square.xyz"
bad missing "no-such.obj: No such file" "shape = mesh" "file = $TD/no-such.obj"
bad noname "no mesh 'middle' with triangles (the file has 'left', 'right')" "shape = mesh" "file = $TD/two.obj" "mesh = middle"
bad nouv "has no UV coordinates, so the bump map of skin 'skin' cannot follow it" "shape = mesh" "file = $TD/square-nouv.obj"
bad nofile "a mesh needs file = PATH" "shape = mesh"
scene nouvok "shape = mesh" "file = $TD/square-nouv.obj"
export_pov nouvok --scene "$tmpd/nouvok.scene" --bake "$B"
check "a mesh without UVs and without a bump map exports" test $? -eq 0

# 5. --size and --unit-mm (the include-only mode).
export_pov sized --bake "$B" --textures "$TX" --light position=1:1:-1 --camera type=perspective,location=0:0:-3 \
	--size 200x100 --unit-mm 2
grep -q "bump_size [0-9.]* } scale 2 }" "$tmpd/sized/skin.inc"
check "--unit-mm 2: a 4 mm tile is 2 units" test $? -eq 0
export_pov sizedbad --bake "$B" --light position=1:1:-1 --camera type=perspective,location=0:0:-3 --size 10x100
check "--size 10x100: exit 2" test $? -eq 2
grep -q "16, 8192" "$tmpd/sizedbad.stderr"
check "--size 10x100: the range in the message" test $? -eq 0
scene sizedscene "shape = patch"
export_pov sizedscene --scene "$tmpd/sizedscene.scene" --bake "$B" --size 200x100
grep -q "Width=200" "$tmpd/sizedscene/sizedscene.ini" && grep -q "Height=100" "$tmpd/sizedscene/sizedscene.ini"
check "--size overrides the scene's image size" test $? -eq 0

tap_done
