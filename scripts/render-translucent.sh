#!/bin/sh
# The gallery of docs/translucency.md (issue 27): the MakeHuman head in POV-Ray 3.7, exact mode
# against translucent mode (POV-Ray's own subsurface fitted to the bake's Rd(r) under the rest of
# the table), lit from the front (scenes/human-head.scene; --lights mixture, which the
# translucent mode needs for its two lights) and from behind the ear (scenes/human-head-earglow.scene,
# one light, the demo's: scripts/demo-translucent.sh), with each render's wall and CPU time.
#   scripts/render-translucent.sh [OUT_DIR]        (default out/translucent)
# Environment: SIZE (default 320x240), PRESET (default paper).  Writes OUT_DIR/pov-{front,back}-
# {exact,translucent}.png and OUT_DIR/times.txt (label wall_s cpu_s).  Run after scripts/setup.sh.
set -eu
cd "$(dirname "$0")/.."
B=${SKINBAKE:-./skinbake}
out=${1:-out/translucent}
size=${SIZE:-320x240}
preset=${PRESET:-paper}
mkdir -p "$out"
: >"$out/times.txt"
if [ ! -f "$out/bake/manifest.json" ]; then
	echo "== bake ($preset, 10 incidence nodes)"
	/usr/bin/time -f "bake %e %U" -a -o "$out/times.txt" $B bake --preset "$preset" --theta-nodes 10 \
		--out "$out/bake" --quiet
fi
for shot in front back; do
	scene=scenes/human-head.scene lights="--lights mixture"
	[ $shot = back ] && scene=scenes/human-head-earglow.scene lights=""
	base=$(basename "$scene" .scene)
	for mode in exact translucent; do
		d="$out/pov-$shot-$mode"
		echo "== $shot, $mode"
		# shellcheck disable=SC2086
		$B export pov --scene "$scene" --bake "$out/bake" --out "$d" --mode $mode $lights \
			--size "$size" >"$d.log" 2>&1 || { cat "$d.log" >&2; exit 1; }
		(cd "$d" && /usr/bin/time -f "pov-$shot-$mode %e %U" -a -o "../times.txt" povray "$base.ini" \
			>povray.log 2>&1) || { echo "render-translucent.sh: povray failed, see $d/povray.log" >&2; exit 1; }
		cp "$d/$base.png" "$out/pov-$shot-$mode.png"
	done
done
cat "$out/times.txt"
