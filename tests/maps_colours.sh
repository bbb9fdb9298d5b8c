#!/bin/sh
# Real skin colours (issue 15, "Numbers and checks"): measured in-vivo
# spectra of Xiao et al. 2016 (tests/data: 7 representative spectra at L*
# percentiles 1-99 and the 7 per-wavelength percentile spectra of all 4392)
# fitted by a fair-oily family over epidermis.melanin x dermis.blood x
# epidermis.thickness (6 x 4 x 3 members; thickness 50-150 um, the project's
# range in shared/skin_data/layer_models.tsv; the preset's 16 wavelengths,
# one angle, no Rd(r) to speak of; about 20 s of CPU).  Asserted: the fitted
# melanin is ordered by the Fitzpatrick type of each colour's ITA class;
# the median CIEDE2000 of both sets is under 1 as measured and once the 4 %
# surface reflection a d/8 (specular included) instrument adds is taken off.
# Not asserted (docs/maps.md): the darkest colour, L* 38, is still 3.3-3.5
# off as measured (the thickness axis ends at 150 um there).
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
M="$top_builddir/tests/maps_check"
D="$top_srcdir/tests/data"
fam="$tmpd/fam"
check "family melanin x blood x epidermis thickness" "$B" bake --preset fair-oily --theta-in 0 --resolution 1x1 --r-bins 10 \
	--radial-photons 100 --radial-error 1 --vary epidermis.melanin=0.005:0.4:6 --vary dermis.blood=0.003:0.1:4 \
	--vary epidermis.thickness=0.005:0.015:3 --out "$fam" --quiet

# fit NAME TABLE R0: spectra less R0 -> swatch -> maps fit; NAME.types
# (index L a b ITA type) and NAME.values (index melanin blood thickness de).
fit() {
	"$M" spectra "$D/$2.tsv" "$tmpd/$1.exr" "$3" > "$tmpd/$1.types" &&
	"$B" maps fit --family "$fam" --albedo "$tmpd/$1.exr" --input linear --max-de 20 --out "$tmpd/$1" --quiet &&
	"$M" values "$tmpd/$1" > "$tmpd/$1.values"
}
# judge NAME MAXMEDIAN: prints the median; fails above MAXMEDIAN (or "-"
# for none) or when melanin is not ordered by type.
judge() {
	paste -d ' ' "$tmpd/$1.types" "$tmpd/$1.values" | awk -v max="$2" '
		{ type[NR] = $6; mel[NR] = $8; de[NR] = $11; n = NR }
		END {
			for (i = 1; i <= n; i++) for (j = 1; j <= n; j++)
				if (type[i] > type[j] && mel[i] <= mel[j]) { printf "type %d melanin %g <= type %d melanin %g; ", type[i], mel[i], type[j], mel[j]; bad = 1 }
			for (i = 1; i <= n; i++) { s[i] = de[i] }
			for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (s[j] < s[i]) { t = s[i]; s[i] = s[j]; s[j] = t }
			med = n % 2 ? s[(n + 1) / 2] : (s[n / 2] + s[n / 2 + 1]) / 2
			printf "median CIEDE2000 %.3f, max %.3f", med, s[n]
			exit bad || (max != "-" && med >= max)
		}'
}
for c in "pct xiao2016_skin_reflectance_percentiles 0 1" "rep xiao2016_representative_spectra_by_Lstar 0 1" \
	"pct_sce xiao2016_skin_reflectance_percentiles 0.04 1" "rep_sce xiao2016_representative_spectra_by_Lstar 0.04 1"; do
	set -- $c
	if fit "$1" "$2" "$3"; then
		r=$(judge "$1" "$4")
		check "$2 less $3: melanin ordered by Fitzpatrick type, $r (median under $4)" test $? -eq 0
	else
		fail "$2: spectra or fit failed"
	fi
done
tap_done
