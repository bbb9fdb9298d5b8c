#!/bin/sh
# The baked BRDF at every angle (issue 26): eval against adding-doubling
# point values (tests/test_grazing, built by `make check`), verify's
# false-alarm rate (tests/test_verify), and what the default table costs.
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
echo "89, 89.9 deg and delta_phi = 0, 10, ..., 180 deg (153,900 points)."
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
"$B" export blender --bake "$T/b" --out "$T/bl" >/dev/null
t1=$(now)
echo "| \`skinbake export blender\` (of the last) | $(echo "$t1 - $t0" | bc -l | cut -c1-5) |"
