#!/bin/sh
# Maps benchmarks (issue 15): the family bake of the issue (fair-oily, epidermis.melanin 8 x
# dermis.blood 6, the preset's 16 wavelengths, default solver auto = adding-doubling, default
# table), the fit of a 2048 x 2048 16-bit albedo texture, and the round trip made-up maps ->
# albedo -> fit -> albedo on it; the fit at 4096 x 4096 with its peak memory (issue 28: under
# 10 s CPU and 400 MB), and the fit's worst case, a 1024 x 1024 albedo with noise of +-40 16-bit
# levels (nearly every texel a distinct colour off the family's surface).  Prints one markdown section.  Wall times depend on the load of
# the machine; CPU times (user + system) are given beside them.  FAMILY=DIR reuses a family of
# these settings instead of baking one (its bake is then not timed); BENCH_QUICK=1 fits 512 x 512.
set -eu
SKINBAKE=${SKINBAKE:-./skinbake}
top_builddir=${top_builddir:-.}
M="$top_builddir/tests/maps_check"
QUICK=${BENCH_QUICK:-0}
N=2048 N4=4096 NN=1024
[ "$QUICK" = 1 ] && N=512 N4=1024 NN=256
W=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench-maps.XXXXXX")
trap 'rm -rf "$W"' EXIT INT TERM
# timed LABEL CMD...: runs CMD, appends "LABEL wall cpu" to $W/times
timed() {
	l=$1
	shift
	/usr/bin/time -f "$l %e %U %S %M" -a -o "$W/times" "$@"
}
fam=${FAMILY:-}
if [ -z "$fam" ]; then
	fam="$W/fam"
	timed family "$SKINBAKE" bake --preset fair-oily --vary epidermis.melanin=0.005:0.3:8 \
		--vary dermis.blood=0.005:0.1:6 --out "$fam" --quiet --threads 2
fi
"$M" synth "$fam" "$W/true" "$N" "$N" >/dev/null
timed render "$SKINBAKE" maps render-albedo --family "$fam" --maps "$W/true" --out "$W/a.png" --quiet
timed fit "$SKINBAKE" maps fit --family "$fam" --albedo "$W/a.png" --out "$W/fit" --quiet --threads 2
"$SKINBAKE" maps render-albedo --family "$fam" --maps "$W/fit" --out "$W/r.png" --quiet
"$M" compare "$fam" "$W/true" "$W/fit" "$W/a.png" "$W/r.png" 0.1 >"$W/cmp.txt"
"$M" compare "$fam" "$W/true" "$W/fit" "$W/a.png" "$W/r.png" 0.5 >"$W/cmp5.txt"
"$M" synth "$fam" "$W/true4" "$N4" "$N4" >/dev/null
"$SKINBAKE" maps render-albedo --family "$fam" --maps "$W/true4" --out "$W/a4.png" --quiet
timed fit4 "$SKINBAKE" maps fit --family "$fam" --albedo "$W/a4.png" --out "$W/fit4" --threads 2 >"$W/fit4.txt"
"$M" synth "$fam" "$W/truen" "$NN" "$NN" >/dev/null
"$SKINBAKE" maps render-albedo --family "$fam" --maps "$W/truen" --out "$W/an.png" --quiet
"$M" noise "$W/an.png" "$W/nn.png" 40
timed fitn "$SKINBAKE" maps fit --family "$fam" --albedo "$W/nn.png" --out "$W/fitn" --threads 2 >"$W/fitn.txt"
# colours FILE: the distinct colours a fit's summary names.
colours() { sed -n 's/.*(\([0-9]*\) distinct colours).*/\1/p' "$1"; }
mb() { awk -v k="$1" '$1 == k { printf "%.0f", $5 / 1024 }' "$W/times"; }
us() { awk -v k="$1" -v n="$2" '$1 == k { printf "%.1f", 1e6 * ($3 + $4) / n }' "$W/times"; }
val() { awk -v k="$1" '$1 == k { print $2 }' "$W/cmp.txt"; }
# pct KEY: the share KEY of the stricter comparison in per cent.
pct() { awk -v k="$1" '$1 == k { printf "%.0f", 100 * $2 }' "$W/cmp5.txt"; }
t() { awk -v k="$1" -v f="$2" '$1 == k { if (f == "wall") printf "%.1f", $2; else printf "%.1f", $3 + $4 }' "$W/times"; }
echo "## Maps"
echo
echo "Machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at the end (wall times grow with it)."
echo
echo "| step | wall [s] | CPU [s] | peak memory [MB] |"
echo "|---|---|---|---|"
if [ -z "${FAMILY:-}" ]; then
	echo "| family bake, fair-oily, melanin 8 x blood 6, 16 wavelengths, 10 angles, 18x18, ad (48 members) | $(t family wall) | $(t family cpu) | $(mb family) |"
fi
echo "| maps render-albedo ${N}x${N} | $(t render wall) | $(t render cpu) | $(mb render) |"
echo "| maps fit ${N}x${N} 16-bit, 2 threads | $(t fit wall) | $(t fit cpu) | $(mb fit) |"
echo "| maps fit ${N4}x${N4} 16-bit ($(colours "$W/fit4.txt") distinct colours), 2 threads | $(t fit4 wall) | $(t fit4 cpu) | $(mb fit4) |"
echo "| maps fit ${NN}x${NN} 16-bit with noise +-40 ($(colours "$W/fitn.txt") distinct colours), 2 threads | $(t fitn wall) | $(t fitn cpu) | $(mb fitn) |"
echo
echo "The fit streams its files (issue 28): the albedo is read in bands of 64 rows for its distinct"
echo "colours and each texel's colour id, and the maps are written band by band from the ids (beyond"
echo "5792^2 texels the albedo is read a second time instead), so its memory is about 40 bytes per"
echo "distinct colour and 4 per texel, not the images. Its CPU time grows with the distinct colours:"
echo "the made-up maps' albedo has fewer at 4096^2 than at 2048^2 (the freckles, 2.5 times the"
echo "melanin, cover most of the larger picture and clip it to the family's end), so the 4096^2 row"
echo "is the easier fit. In the noisy case it is about $(us fitn "$(colours "$W/fitn.txt")") us per distinct colour (the warm"
echo "start from the previous colour rarely reaches an exact match there, so most colours are solved"
echo "twice), and a 16-bit texture whose texels are nearly all distinct colours is far slower."
echo
echo "Round trip on the ${N}x${N} made-up maps (smooth fields plus freckles): median CIEDE2000 of the"
echo "re-rendered albedo $(val de2000_median) (95th percentile $(val de2000_p95), max $(val de2000_max));"
for k in epidermis.melanin dermis.blood; do
	echo "$k: $(val ${k}_sensitive_share) of the texels are sensitive (a 5 % change moves the colour by"
	echo "0.1 CIEDE2000 or more), of which $(val ${k}_within_5pct_share) are within 5 % (max relative error $(val ${k}_relerr_max))."
done
echo
echo "At the issue's stricter reading of \"sensitive\" (a 5 % change moves the colour by 0.5 CIEDE2000 or"
echo "more; \`maps_check compare ... 0.5\`, same maps) $(pct epidermis.melanin_sensitive_share) % of the texels are"
echo "sensitive to melanin and $(pct dermis.blood_sensitive_share) % to blood; where a share is small, a 5 % change of"
echo "that parameter moves these colours by less than 0.5 CIEDE2000, and it is recovered as above only"
echo "because the round trip has no noise."
echo
echo "Wall times are for the machine's load at the time (above); the CPU times divided by the cores are"
echo "what an idle machine takes.  Most of the family's time is the Monte Carlo Rd(r) run (the"
echo "subsurface radius) beside the adding-doubling tables.  Commands: \`sh scripts/bench-maps.sh\`"
echo "(\`FAMILY=DIR\` reuses a family; \`BENCH_QUICK=1\` fits 512 x 512)."
