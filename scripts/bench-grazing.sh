#!/bin/sh
# The baked BRDF at every angle (issue 26): eval against adding-doubling
# point values (tests/test_grazing, built by `make check`), verify's
# false-alarm rate (tests/test_verify), what the default table costs, POV-Ray
# renders' silhouettes against adding-doubling (tests/pov_compare, as
# tests/pov_silhouette.sh) and the node schedule's hard cases (simulate).
# Prints a markdown section (make bench).
set -eu
B=${SKINBAKE:-./skinbake}
TB=${top_builddir:-.}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
now() { date +%s.%N; }
echo "## Grazing angles (issue 26)"
echo
echo "Machine: $(nproc) cores, $(uname -m); $(date -u +%Y-%m-%d)."
echo
echo "### eval against adding-doubling point values"
echo
echo "\`tests/test_grazing\`: a default adding-doubling bake (fair-oily, 550 nm, \`--resolution 18x18\`,"
echo "the default incidence nodes 0 to 89.2 deg) through \`bake_eval_diffuse\`, against point values of"
echo "a separate solve at 64 nodes per unit cosine and tolerance 1e-4, on theta_i, theta_o = 1, 2, ...,"
echo "89, 89.9 deg and delta_phi = 0, 10, ..., 180 deg (153,900 points); \"bin means\": the same bake"
echo "written as bin means (what Monte Carlo tables hold), which eval reads linearly, its error"
echo "including what that costs (src/bake/bakeinterp.h)."
echo
if [ -x "$TB/tests/test_grazing" ]; then
	echo '```'
	"$TB/tests/test_grazing" 2>&1 | grep '^#' | sed 's/^# //'
	echo '```'
else
	echo "(tests/test_grazing not built: run make check first)"
fi
echo
echo "Before issue 26 (bin means read as point values, incidence nodes 0 to 81 deg, the last value"
echo "held) the same comparison gave interior RMS 1.1 %, worst 4.5 %, with a reported error of"
echo "about 1e-5 relative; +187 % at theta_o 89 deg and +1,061 % at theta_i 89.5 deg (issue 26)."
echo
echo "### verify: false alarms on right tables, a table 1 % off"
echo
if [ -x "$TB/tests/test_verify" ]; then
	echo '```'
	"$TB/tests/test_verify" 2>&1 | grep '^#' | sed 's/^# //'
	echo '```'
fi
echo
echo "### The default table's cost"
echo
echo "| command | wall [s] |"
echo "|---|---|"
for args in "--preset fair-oily" "--preset fair-oily --theta-nodes 10"; do
	t0=$(now)
	# shellcheck disable=SC2086
	"$B" bake $args --out "$T/b" --quiet --r-bins 50 >/dev/null
	t1=$(now)
	echo "| \`skinbake bake $args\` | $(echo "$t1 - $t0" | bc -l | cut -c1-5) |"
done
t0=$(now)
"$B" export blender --bake "$T/b" --out "$T/bl" --mode exact >/dev/null
t1=$(now)
echo "| \`skinbake export blender\` (of the last) | $(echo "$t1 - $t0" | bc -l | cut -c1-5) |"
echo
# Renders (tests/pov_silhouette.sh's measurement): the sphere scene from a default adding-doubling
# bake of paper (9 x 9) rendered by POV-Ray, against adding-doubling point values of the bake's
# own stacks at each pixel's angles, on the grazing ring; and the same with 4 incidence nodes.
POVRAY=${POVRAY:-povray}
TS=${top_srcdir:-.}
echo "### Renders: silhouettes against adding-doubling"
echo
if command -v "$POVRAY" >/dev/null 2>&1 && [ -x "$TB/tests/pov_compare" ]; then
	. "$TS/tests/lib/pov.sh"
	echo "\`tests/pov_compare expect --ad\` on a POV-Ray render (128 x 128) of \`scenes/sphere.scene\`: the"
	echo "mean relative error against adding-doubling point values of the bake's own stacks at each"
	echo "pixel's angles (pixels with the exit angle shown), and against eval over the whole sphere."
	echo
	echo "| bake | exit >= 60 deg | >= 70 deg | >= 75 deg | whole sphere against eval |"
	echo "|---|---|---|---|---|"
	for nodes in "" "--theta-nodes 4"; do
		# shellcheck disable=SC2086
		"$B" bake --preset paper --resolution 9x9 --r-bins 20 --radial-photons 4000 $nodes --out "$T/s" \
			--quiet >/dev/null
		rm -rf "$T/sp"
		"$B" export pov --out "$T/sp" --data-dir "$TS/exporters/pov" --scene "$TS/scenes/sphere.scene" \
			--bake "$T/s" >/dev/null 2>&1
		pov_render "$T/sp" sphere 128 128 >/dev/null
		row="| \`skinbake bake --preset paper --resolution 9x9${nodes:+ $nodes}\` |"
		for m in 60 70 75; do
			r=$("$TB/tests/pov_compare" expect --scene "$TS/scenes/sphere.scene" --bake "$T/s" \
				--render "$T/sp/r.png" --ad --min-theta-out $m --tol 1 | head -1 | awk '{ printf "%.2f %% (%d px)", 100 * $2, $6 }')
			row="$row $r |"
		done
		r=$("$TB/tests/pov_compare" expect --scene "$TS/scenes/sphere.scene" --bake "$T/s" \
			--render "$T/sp/r.png" --tol 1 | head -1 | awk '{ printf "%.2f %% (%d px)", 100 * $2, $6 }')
		echo "$row $r |"
	done
else
	echo "(POV-Ray or tests/pov_compare missing: run make check first)"
fi
echo
# The node schedule: cases that needed more than 32 nodes per unit cosine (issue 26).
echo "### Node schedule"
echo
echo "| \`skinbake simulate --solver ad --ad-tol 1e-3 --json\` | nodes per unit cosine | estimated table error | Rd | wall [s] |"
echo "|---|---|---|---|---|"
for L in "--layer d=0.1,n=1.4,mua=1,mus=100,g=0.99 --theta-in 0" \
	"--layer d=0.0000099,n=1.4,mua=1,mus=100,g=0.8 --theta-in 0" \
	"--layer d=0.0000099,n=1.4,mua=1,mus=100,g=0.8 --theta-in 34" \
	"--layer d=0.0000099,n=1.4,mua=1,mus=100,g=0.8 --theta-in 80"; do
	t0=$(now)
	# shellcheck disable=SC2086
	"$B" simulate $L --solver ad --ad-tol 1e-3 --json >"$T/ns.json"
	t1=$(now)
	python3 - "$T/ns.json" "$L" "$(echo "$t1 - $t0" | bc -l | cut -c1-5)" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print("| `%s` | %d | %.2g | %.5f | %s |" % (sys.argv[2], d["n_quad"], d["rms_rel_err"], d["Rd"], sys.argv[3]))
PY
done
