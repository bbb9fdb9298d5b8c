#!/bin/sh
# tests/brdf_points (the validation report's and the CUReT fit's evaluator)
# against `skinbake eval` on one small bake: the same numbers at a few
# geometries, --alpha changes only the specular part, bad input is rejected.
# Cost: one bake of 2 angles x 3 wavelengths x 6 x 4 bins (adding-doubling by
# default since the solver merge; about 1 s).
. "$top_srcdir/tests/tap.sh"
BP=$top_builddir/tests/brdf_points
B=$tmpd/bake
"$SKINBAKE" bake --preset paper --out "$B" --theta-in 10,40 --resolution 6x4 --target-error 0 \
	--max-photons 48000 --batch-photons 1000 --threads 1 --quiet && ok "small bake" || fail "small bake"
printf '10 20 0\n25 50 180\n40 75 90\n' >"$tmpd/pts"
"$BP" "$B" <"$tmpd/pts" >"$tmpd/out" && [ "$(wc -l <"$tmpd/out")" -eq 3 ] \
	&& ok "three points, three lines" || fail "brdf_points output: $(cat "$tmpd/out")"
# skinbake eval: the mean over the wavelengths of total, diffuse, specular.
i=0
while read -r ti to ph; do
	i=$((i + 1))
	ev=$("$SKINBAKE" eval --bake "$B" --theta-in "$ti" --theta-out "$to" --phi "$ph" --json |
		jq -r '[(.total | add / length), (.diffuse | add / length), (.specular | add / length)] | @tsv')
	bp=$(sed -n "${i}p" "$tmpd/out" | cut -f1-3)
	# brdf_points prints 6 significant digits.
	printf '%s\t%s\n' "$ev" "$bp" | awk -F'\t' 'NF != 6 || $2 <= 0 { exit 1 } { for (k = 1; k <= 3; k++) { d = $k - $(k + 3); if (d < 0) d = -d;
		if (d > 1e-5 * ($k > 0 ? $k : 1)) exit 1 } }' \
		&& ok "point $i ($ti $to $ph) as skinbake eval" || fail "point $i: eval $ev, brdf_points $bp"
done <"$tmpd/pts"
# --alpha: the diffuse column is unchanged, the specular one changes.
"$BP" "$B" --alpha 0.6 <"$tmpd/pts" >"$tmpd/out6"
paste "$tmpd/out" "$tmpd/out6" | awk -F'\t' 'NF != 8 || $2 != $6 || $3 == $7 { bad = 1 } END { exit bad || NR != 3 }' \
	&& ok "--alpha changes only the specular part" || fail "--alpha: $(paste "$tmpd/out" "$tmpd/out6")"
rc=0; echo "10 20" | "$BP" "$B" >/dev/null 2>"$tmpd/err" || rc=$?
[ "$rc" = 2 ] && grep -q "line 1" "$tmpd/err" && ok "short line rejected" || fail "short line: rc $rc"
rc=0; "$BP" "$B" --alpha 3 </dev/null 2>"$tmpd/err" || rc=$?
[ "$rc" = 2 ] && grep -q "0.01, 1" "$tmpd/err" && ok "--alpha out of range rejected" || fail "--alpha 3: rc $rc"
tap_done
