#!/bin/sh
# Render every scene in scenes/ with POV-Ray into docs/img/pov-NAME.png
# (8-bit sRGB previews for docs/pov.md), but the MakeHuman ones: their
# images come from scripts/demo.sh, with the bake the demo plans.
#
#   scripts/render-scenes.sh [WORKDIR]
#
# Environment: SKINBAKE (default ./skinbake), POVRAY (default povray),
# PHOTONS (bake photon budget, default 3e6), THREADS (default 0 = all).
# Bakes (paper, paper-dry) and micro-geometry maps (face, hand) are made in
# WORKDIR (default ./render-work) and reused when present.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
SKINBAKE=${SKINBAKE:-./skinbake}
POVRAY=${POVRAY:-povray}
PHOTONS=${PHOTONS:-3e6}
THREADS=${THREADS:-0}
work=${1:-render-work}
mkdir -p "$work" "$top/docs/img"
SKINBAKE=$(cd "$(dirname "$SKINBAKE")" && pwd)/$(basename "$SKINBAKE")
work=$(cd "$work" && pwd)

for p in paper paper-dry; do
	[ -f "$work/bake-$p/manifest.json" ] ||
		"$SKINBAKE" bake --preset "$p" --out "$work/bake-$p" --estimator bins \
			--max-photons "$PHOTONS" --target-error 0 --threads "$THREADS" --quiet
done
for s in $(sed -n 's/^site *= *//p' "$top"/scenes/*.scene | sort -u); do
	[ -f "$work/tex-$s/height.png" ] ||
		"$SKINBAKE" texture --site "$s" --size 512 --out "$work/tex-$s" --quiet
done

for f in "$top"/scenes/*.scene; do
	n=$(basename "$f" .scene)
	case $n in human-*) continue ;; esac
	site=$(sed -n 's/^site *= *//p' "$f" | head -1)
	out="$work/$n"
	dry=""
	grep -q '^\[skin dry\]' "$f" && dry="--bake dry=$work/bake-paper-dry"
	# shellcheck disable=SC2086
	"$SKINBAKE" export pov --scene "$f" --bake "$work/bake-paper" $dry \
		--textures "$work/tex-$site" --data-dir "$top/exporters/pov" --out "$out" >/dev/null 2>"$out.log" ||
		{ cat "$out.log"; exit 1; }
	t0=$(date +%s)
	(cd "$out" && "$POVRAY" "$n.ini" >pov.log 2>&1) || { tail -20 "$out/pov.log"; exit 1; }
	cp "$out/$n.png" "$top/docs/img/pov-$n.png"
	echo "$n: $(($(date +%s) - t0)) s, $(wc -c <"$top/docs/img/pov-$n.png") bytes"
done
