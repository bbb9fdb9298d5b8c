#!/bin/sh
# Translucent mode benchmark, Cycles half (issue 27): render time of the MakeHuman head in
# Debian's Blender, exact against translucent mode and the five-minute baseline, front and back
# lit, at the gallery's size (scripts/render-translucent-blender.sh, SIZE default 320x240, 32
# samples).  Prints one markdown section.  RENDER_DIR=DIR reuses a finished
# render-translucent-blender.sh run (its times.txt: "label wall_s cpu_s") instead of rendering;
# RENDER_LOAD then says the load average it was rendered at.
set -eu
top_srcdir=${top_srcdir:-.}
dir=${RENDER_DIR:-}
if [ -z "$dir" ]; then
	dir=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench-transl-bl.XXXXXX")
	trap 'rm -rf "$dir"' EXIT INT TERM
	SKINBAKE=${SKINBAKE:-./skinbake} sh "$top_srcdir/scripts/render-translucent-blender.sh" "$dir" >/dev/null
	load="load $(cut -d' ' -f1 /proc/loadavg) when rendered"
else
	load="times of a reused run, load ${RENDER_LOAD:-not recorded} when rendered"
fi
t() { awk -v k="$1" -v f="$2" '$1 == k { print $f }' "$dir/times.txt"; }
ratio() { awk -v a="$(t "$1" 3)" -v b="$(t "$2" 3)" 'BEGIN { printf "%.1f", b / a }'; }
cat <<EOT
## Translucent mode (Cycles)

The MakeHuman head at ${SIZE:-320x240}, ${SAMPLES:-32} samples (\`scripts/render-translucent-blender.sh\`;
\`paper\`, 10 incidence nodes; Debian's Blender, Cycles CPU), $(uname -m), $load; CPU is user
time of the Blender process (wall times grow with the load):

| shot | exact wall / CPU [s] | translucent wall / CPU [s] | five-minute baseline wall / CPU [s] | CPU ratio translucent / exact |
|---|---|---|---|---|
| front (human_scene.py key + fill) | $(t blender-front-exact 2) / $(t blender-front-exact 3) | $(t blender-front-translucent 2) / $(t blender-front-translucent 3) | $(t blender-front-baseline 2) / $(t blender-front-baseline 3) | $(ratio blender-front-exact blender-front-translucent) |
| back (the key sun behind the head) | $(t blender-back-exact 2) / $(t blender-back-exact 3) | $(t blender-back-translucent 2) / $(t blender-back-translucent 3) | $(t blender-back-baseline 2) / $(t blender-back-baseline 3) | $(ratio blender-back-exact blender-back-translucent) |
EOT
