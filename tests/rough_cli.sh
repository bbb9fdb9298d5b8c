#!/bin/sh
# Rough boundaries from the command line (issue 21): the preset keys'
# ranges and the boundaries they need (exit 2, the key and value named, no
# output), simulate --layer rough=, a small Monte Carlo bake of a rough
# preset (the manifest books the facet loss) and an `--solver ad` bake with
# multiple scattering on the facets (its physics: tests/test_ad_rough).
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"

# bad NAME INI-TEXT PATTERN: preset show of that preset file refused (tests/lib/refused.sh)
bad() {
	printf '%b' "$2" >"$tmpd/$1.ini"
	refused_quiet=1
	refused "$1: exit 2, '$3'" "$3" "" "$SKINBAKE" preset show --preset-file "$tmpd/$1.ini"
}
bad negative '[skin]\nbase = fair-dry\n[surface]\nroughness = -0.1\n' 'surface.roughness = -0.1: out of range \[0, 1\]'
bad above1 '[skin]\nbase = fair-dry\n[surface]\nroughness = 1.01\n' 'surface.roughness = 1.01: out of range'
bad layer_above1 '[skin]\nbase = fair-oily\n[dermis]\ntop_roughness = 2\n' 'dermis.top_roughness = 2: out of range'
bad ms_half '[skin]\nbase = fair-dry\n[surface]\nmultiple_scattering = 0.5\n' 'surface.multiple_scattering = 0.5: must be 0 or 1'
bad no_film '[skin]\nbase = fair-dry\n[epidermis]\ntop_roughness = 0.2\n' 'epidermis.top_roughness = 0.2 but there is no sebum film'
bad no_subcutis '[skin]\nbase = fair-dry\n[subcutis]\nthickness = 0\ntop_roughness = 0.2\n' 'subcutis.top_roughness = 0.2 but the preset has no subcutis'

# Smooth presets keep their resolved text: the rough keys appear only when set.
"$SKINBAKE" preset show fair-oily --ini | grep -q 'roughness = ' && fail "smooth preset text has a transport roughness" \
	|| ok "smooth preset text unchanged (no transport roughness key)"
printf '[skin]\nbase = fair-oily\n[surface]\nroughness = 0.3\n[epidermis]\ntop_roughness = 0.4\n' >"$tmpd/r.ini"
"$SKINBAKE" preset show --preset-file "$tmpd/r.ini" --ini >"$tmpd/r2.ini" \
	&& grep -q '^roughness = 0.3$' "$tmpd/r2.ini" && grep -q '^top_roughness = 0.4$' "$tmpd/r2.ini" \
	&& ok "rough keys in the resolved text" || fail "rough keys in the resolved text"
"$SKINBAKE" preset keys | grep -q '^surface.roughness .*\[0, 1\]' && ok "preset keys lists surface.roughness" \
	|| fail "preset keys lists surface.roughness"

"$SKINBAKE" simulate --layer d=inf,n=1.4,mua=1,mus=100,g=0.8,rough=1.5 >"$tmpd/out" 2>"$tmpd/err"
[ $? -eq 2 ] && grep -q 'rough' "$tmpd/err" && ok "simulate rough=1.5: exit 2" || fail "simulate rough=1.5"
"$SKINBAKE" simulate --layer d=inf,n=1.4,mua=1,mus=100,g=0.8,rough=0.3 --photons 20000 --json >"$tmpd/sim.json" \
	&& python3 -c "
import json, sys
r = json.load(open('$tmpd/sim.json'))
s = r['Rsp'] + r['Rd'] + r['Tt'] + sum(r['A']) + r['lost'] + r['facet_loss']
sys.exit(0 if abs(s - 1) < 1e-9 and r['facet_loss'] > 0 and r['Rsp_err'] > 0 else 1)" \
	&& ok "simulate rough: balance with the facet loss" || fail "simulate rough: balance"

printf '[skin]\nbase = fair-oily\n[surface]\nroughness = 0.3\nmultiple_scattering = 1\n' >"$tmpd/ms.ini"
"$SKINBAKE" bake --preset-file "$tmpd/ms.ini" --solver ad --out "$tmpd/ad" --theta-nodes 2 --resolution 6x4 \
	--wavelengths 550 --quiet >"$tmpd/out" 2>"$tmpd/err" \
	&& python3 -c "
import json, sys
m = json.load(open('$tmpd/ad/manifest.json'))
sys.exit(0 if m['solver']['name'] == 'ad' and '\"rough_multiple\":1' in open('$tmpd/ad/manifest.json').read() else 1)" \
	&& ok "bake --solver ad with multiple scattering on the facets (ad_rough.h walk tables)" \
	|| fail "bake --solver ad, multiple scattering: $(cat "$tmpd/err")"
"$SKINBAKE" simulate --layer d=inf,n=1.4,mua=1,mus=100,g=0.8,rough=0.3 --solver ad --ad-quad 16 --json >"$tmpd/ad.json" \
	&& python3 -c "
import json, sys
r = json.load(open('$tmpd/ad.json'))
s = r['Rsp'] + r['Rd'] + r['Tt'] + sum(r['A']) + r['facet_loss']
sys.exit(0 if abs(s - 1) < 1e-9 and r['facet_loss'] > 0 and r['solver'] == 'ad' else 1)" \
	&& ok "simulate --solver ad rough: the facet loss closes the balance" || fail "simulate --solver ad rough"
"$SKINBAKE" bake --preset-file "$tmpd/r.ini" --solver mc --out "$tmpd/b" --theta-nodes 2 --resolution 6x4 --wavelengths 550 \
	--target-error 0.3 --batch-photons 500 --quiet 2>"$tmpd/err" \
	&& python3 -c "
import json, sys
m = json.load(open('$tmpd/b/manifest.json'))
txt = json.dumps(m)
sys.exit(0 if '\"facet_loss\"' in txt and '\"rough_top\"' in txt else 1)" \
	&& ok "bake --solver mc of a rough preset; manifest has rough_top and facet_loss" \
	|| fail "rough bake: $(cat "$tmpd/err")"
tap_done
