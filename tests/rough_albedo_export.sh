#!/bin/sh
# Blender's albedo image past the albedo curve's last node (issue 21, round 6):
# a smooth top lets nothing in at grazing, so the directional albedo a(theta)
# goes linearly to 0 at 90 deg; a rough top (the manifest's rough_top) lets
# light in there, and the curve goes instead to the table's own a(90) =
# 2 int f_d(90, o) cos(theta_o) domega (bake_eval_diffuse_rgb's grazing
# completion, docs/grazing.md).  The exported bihemispherical albedo
# (manifest albedo_rgb, R) must equal 2 int a(mu) mu dmu with that end, computed
# here from the manifest's albedo_curve and tests/brdf_points at theta_i 90
# (the same midpoint rules, so within 1e-6 relative plus the 9 printed digits);
# the smooth bake keeps the ramp to 0.  Cost: two small Monte Carlo bakes at
# 550 nm, 2 angles (a few seconds), two exports.
. "$top_srcdir/tests/tap.sh"
BP=$top_builddir/tests/brdf_points
command -v jq >/dev/null 2>&1 || { skip "jq not installed"; tap_done; exit; }
for k in rough smooth; do
	r=0
	[ $k = rough ] && r=0.4
	printf '[skin]\nbase = fair-dry\nname = %s\n[surface]\nroughness = %s\n' $k $r >"$tmpd/$k.ini"
	"$SKINBAKE" bake --preset-file "$tmpd/$k.ini" --solver mc --wavelengths 550 --theta-in 10,60 --target-error 0.3 \
		--batch-photons 200 --threads 1 --out "$tmpd/$k" --quiet && ok "$k bake" || fail "$k bake"
	"$SKINBAKE" export blender --bake "$tmpd/$k" --out "$tmpd/$k-bl" --mode exact >/dev/null 2>&1 \
		&& ok "$k: export blender" || fail "$k: export blender"
	# a(90): the diffuse at theta_i 90 over 64 x 48 midpoints (cos theta_o, delta_phi over [0, 180]).
	awk 'BEGIN { for (u = 0; u < 64; u++) for (p = 0; p < 48; p++)
		printf "90 %.12g %.12g\n", atan2(sqrt(1 - ((u + 0.5) / 64) ^ 2), (u + 0.5) / 64) * 180 / 3.14159265358979, 180 * (p + 0.5) / 48 }' \
		>"$tmpd/p90"
	a90=$("$BP" "$tmpd/$k" <"$tmpd/p90" | awk -F'\t' '{ u = int((NR - 1) / 48); s += $2 * (u + 0.5) / 64 }
		END { printf "%.10g", s / 64 * 2 * 3.14159265358979 / 48 }')
	[ $k = smooth ] && a90=0
	exp=$(jq -r '.albedo_curve | [(.theta_i_deg | map(tostring) | join(",")), (.R | map(tostring) | join(","))] | join(" ")' \
		"$tmpd/$k-bl/manifest.json" | awk -v a90="$a90" '{ n = split($1, t, ","); split($2, a, ",");
		pi = 3.14159265358979; s = 0
		for (i = 0; i < 4096; i++) { mu = (i + 0.5) / 4096; th = atan2(sqrt(1 - mu * mu), mu) * 180 / pi
			if (th <= t[1]) v = a[1]
			else if (th >= t[n]) { f = (th - t[n]) / (90 - t[n]); v = (1 - f) * a[n] + f * a90 }
			else { for (j = 1; j < n - 1 && th > t[j + 1]; j++); f = (th - t[j]) / (t[j + 1] - t[j]); v = (1 - f) * a[j] + f * a[j + 1] }
			s += v * mu }
		printf "%.10g", 2 * s / 4096 }')
	got=$(jq -r '.albedo_rgb[0]' "$tmpd/$k-bl/manifest.json")
	awk -v g="$got" -v e="$exp" 'BEGIN { d = g - e; if (d < 0) d = -d; exit !(e > 0 && d <= 1e-6 * e + 1e-8) }' \
		&& ok "$k: albedo_rgb R $got = 2 int a mu dmu with a(90) = $a90 ($exp)" \
		|| fail "$k: albedo_rgb R $got, expected $exp (a(90) = $a90)"
done
tap_done
