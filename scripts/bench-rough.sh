#!/bin/sh
# Rough boundaries (issue 21), in CPU seconds (user + system; the machine is shared), the
# smallest of REPS runs (default 3):
#   1. the Monte Carlo kernel per photon on a skin stack (5 um clear film, epidermis, dermis),
#      smooth against a rough top (GGX alpha 0.3): `simulate`, one thread;
#   2. a bake to equal target error, smooth (next-event estimation on) against the rough top
#      (escapes only: next-event estimation follows smooth refraction), single and multiple
#      scattering on the facets, --solver mc;
#   3. adding-doubling on the stack of 1, smooth against the rough top, at fixed quadratures
#      (`simulate --solver ad --ad-quad N`, one thread; each solve includes the one at N/2 for
#      the error estimate): the cost of the rough interface (its facets once, then its matrices
#      and the full adding per Fourier order);
#   4. `bake --solver ad` of a preset, smooth, rough top (single and multiple scattering on the
#      facets) and two rough interfaces (film top and epidermis top), at 32 and 64 nodes and the
#      automatic schedule (tolerance 1e-3, doubling up to 256 nodes).
# Prints one markdown section.
set -eu
SKINBAKE=${SKINBAKE:-./skinbake}
REPS=${REPS:-3}
W=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench-rough.XXXXXX")
trap 'rm -rf "$W"' EXIT INT TERM

. "$(dirname "$0")/bench-lib.sh"

echo "## Rough boundaries (issue 21)"
echo
echo "\`scripts/bench-rough.sh\` (REPS=$REPS): CPU seconds (user + system), the smallest of REPS runs."
echo
stack() { # rough of the top
	echo "--layer d=0.0005,n=1.5,mua=0,mus=0,rough=$1 --layer d=0.006,n=1.44,mua=20,mus=300,g=0.8"
	echo "--layer d=inf,n=1.38,mua=2,mus=200,g=0.85"
}
echo "| Monte Carlo kernel, 100000 photons, 1 thread, θi 30° | CPU [s] | Rd | facet loss |"
echo "|---|---|---|---|"
for a in 0 0.3; do
	# shellcheck disable=SC2046
	t=$(cpu "$SKINBAKE" simulate $(stack "$a") --photons 100000 --threads 1 --theta-in 30)
	# shellcheck disable=SC2046
	"$SKINBAKE" simulate $(stack "$a") --photons 100000 --threads 1 --theta-in 30 --json >"$W/s.json"
	echo "| top α = $a | $t | $(jq -r '"\(.Rd * 1000 | round / 1000)"' "$W/s.json") | $(jq -r '(.facet_loss // 0) * 1000 | round / 1000' "$W/s.json") |"
done
echo
printf '[skin]\nbase = fair-oily\n[surface]\nroughness = 0.3\n' >"$W/rough.ini"
printf '[skin]\nbase = fair-oily\n[surface]\nroughness = 0.3\nmultiple_scattering = 1\n' >"$W/roughms.ini"
echo "| \`bake\` fair-oily, 550 nm, 2 incidence nodes, 9x6 bins, target 0.02, --solver mc | CPU [s] | photons | table RMS rel. error |"
echo "|---|---|---|---|"
for src in "--preset fair-oily" "--preset-file $W/rough.ini" "--preset-file $W/roughms.ini"; do
	# shellcheck disable=SC2086
	t=$(cpu "$SKINBAKE" bake $src --solver mc --wavelengths 550 --theta-nodes 2 --resolution 9x6 \
		--target-error 0.02 --batch-photons 1000 --out "$W/b" --quiet)
	case $src in
	*roughms*) l="top α = 0.3, multiple scattering on the facets (escapes)" ;;
	*rough*) l="top α = 0.3, single scattering (escapes)" ;;
	*) l="smooth (next-event estimation)" ;;
	esac
	echo "| $l | $t | $(jq -r '.result.photons' "$W/b/manifest.json") | $(jq -r '.result.rms_rel_err * 1000 | round / 1000' "$W/b/manifest.json") |"
done
echo
echo "The smooth bake meets the target with its minimum of batches, so 9-10 times is the least"
echo "a rough top costs here; without next-event estimation the bins fill from the escapes only."
echo
echo "| adding-doubling, stack above, θi 30°, 1 thread | nodes per unit cosine | CPU [s] | Fourier orders | Rd | facet loss | table error estimate |"
echo "|---|---|---|---|---|---|---|"
for a in 0 0.3; do
	for nq in 32 64; do
		# shellcheck disable=SC2046
		t=$(cpu "$SKINBAKE" simulate $(stack "$a") --solver ad --ad-quad "$nq" --threads 1 --theta-in 30)
		# shellcheck disable=SC2046
		"$SKINBAKE" simulate $(stack "$a") --solver ad --ad-quad "$nq" --threads 1 --theta-in 30 --json >"$W/s.json"
		echo "| top α = $a | $nq | $t | $(jq -r '.fourier_orders' "$W/s.json") | $(jq -r '.Rd * 10000 | round / 10000' "$W/s.json") | $(jq -r '(.facet_loss // 0) * 10000 | round / 10000' "$W/s.json") | $(jq -r '.rms_rel_err * 10000 | round / 10000' "$W/s.json") |"
	done
done
echo
printf '[skin]\nbase = fair-oily\n[surface]\nroughness = 0.2\nmultiple_scattering = 1\n[epidermis]\ntop_roughness = 0.45\n' \
	>"$W/two.ini"
echo "| \`bake --solver ad\` fair-oily, 550 nm, 2 incidence nodes, 9x6 bins | nodes per unit cosine | CPU [s] | table error estimate |"
echo "|---|---|---|---|"
for src in "--preset fair-oily" "--preset-file $W/rough.ini" "--preset-file $W/roughms.ini" "--preset-file $W/two.ini"; do
	case $src in
	*two*) l="film top α = 0.2 and epidermis top α = 0.45, multiple scattering" ;;
	*roughms*) l="top α = 0.3, multiple scattering on the facets" ;;
	*rough*) l="top α = 0.3, single scattering" ;;
	*) l="smooth" ;;
	esac
	for nq in 32 64 auto; do
		q="--ad-quad $nq"
		[ "$nq" = auto ] && q=""
		# shellcheck disable=SC2086
		t=$(cpu "$SKINBAKE" bake $src --solver ad $q --wavelengths 550 --theta-nodes 2 --resolution 9x6 \
			--threads 1 --out "$W/b" --quiet) || t=refused
		e=$(jq -r '.solver.rms_rel_err * 10000 | round / 10000' "$W/b/manifest.json" 2>/dev/null || echo -)
		[ "$nq" = auto ] && nq="auto ($(jq -r '[.. | objects | .n_quad? // empty | numbers] | max // "-"' "$W/b/manifest.json" 2>/dev/null || echo -))"
		echo "| $l | $nq | $t | $e |"
		rm -rf "$W/b"
	done
done
echo
echo "Multiple scattering on the facets in adding-doubling: the walk tables of src/engine/ad_rough.h"
echo "(8192 walks at each of 24 incoming cosines per side, once per interface and quadrature)."
