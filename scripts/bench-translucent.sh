#!/bin/sh
# Translucent mode benchmark (issue 27): render time of the MakeHuman head in POV-Ray, exact
# against translucent mode, front and back lit, at the gallery's size (scripts/render-translucent.sh,
# SIZE default 320x240).  Prints one markdown section.  RENDER_DIR=DIR reuses a finished
# render-translucent.sh run (its times.txt) instead of rendering.  Wall times depend on the load
# of the machine; CPU times (user, POV-Ray's two threads) are given beside them.
set -eu
top_srcdir=${top_srcdir:-.}
dir=${RENDER_DIR:-}
if [ -z "$dir" ]; then
	dir=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench-transl.XXXXXX")
	trap 'rm -rf "$dir"' EXIT INT TERM
	SKINBAKE=${SKINBAKE:-./skinbake} sh "$top_srcdir/scripts/render-translucent.sh" "$dir" >/dev/null
fi
t() { awk -v k="$1" -v f="$2" '$1 == k { print $f }' "$dir/times.txt"; }
cat <<EOT
## Translucent mode (POV-Ray)

The MakeHuman head at ${SIZE:-320x240} (\`scripts/render-translucent.sh\`; \`paper\`, 10 incidence
nodes; front: lights mixture, back: one light, key; POV-Ray $(povray --version 2>&1 | sed -n \
's/^POV-Ray \([0-9.]*[0-9]\).*/\1/p' | head -1), 2 threads), $(uname -m), load $(cut -d' ' -f1 /proc/loadavg)
when the section was written:

| shot | exact wall / CPU [s] | translucent wall / CPU [s] | CPU ratio |
|---|---|---|---|
| front-lit (scenes/human-head.scene) | $(t pov-front-exact 2) / $(t pov-front-exact 3) | $(t pov-front-translucent 2) / $(t pov-front-translucent 3) | $(awk -v a="$(t pov-front-exact 3)" -v b="$(t pov-front-translucent 3)" 'BEGIN { printf "%.0f", b / a }') |
| lit from behind the ear (scenes/human-head-earglow.scene, the demo's) | $(t pov-back-exact 2) / $(t pov-back-exact 3) | $(t pov-back-translucent 2) / $(t pov-back-translucent 3) | $(awk -v a="$(t pov-back-exact 3)" -v b="$(t pov-back-translucent 3)" 'BEGIN { printf "%.0f", b / a }') |

POV-Ray's subsurface traces a sample ray and its shadow rays per pixel into a 100,000-triangle
mesh, with adaptive antialiasing (0.3) triggered by its grain.
EOT
