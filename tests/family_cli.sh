#!/bin/sh
# skinbake bake --vary: a small family with the default solver (auto =
# adding-doubling; 2 x 2 members, 4 wavelengths, one angle, a 1 x 1 table;
# about 3 s): the documented directory, family.json agreeing with the
# members' own files, the same member tables and solver record as plain
# bakes of its parameters, the same tables over 1 and 2 MPI ranks; a 2-member
# Monte Carlo family (--solver mc, about 2 s) likewise; bad input exits 2
# and writes nothing.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
B="$SKINBAKE"
small="--wavelengths 400:700:100 --theta-in 0 --resolution 1x1 --target-error 0.1 --batch-photons 500 --r-bins 50 --seed 3"
fam="$tmpd/fam"
check "family bake" "$B" bake --preset fair-oily $small --vary epidermis.melanin=0.01:0.2:2:log \
	--vary dermis.blood=0.01,0.06 --out "$fam" --quiet --threads 2
for f in family.json preset.ini swatches.png m0000/brdf.exr m0003/manifest.json; do
	check "family wrote $f" [ -s "$fam/$f" ]
done
check "no staging left behind" [ ! -e "$fam.staging" ]
check "family.json: axes, members, albedo agreeing with each member's albedo.exr manifest" python3 -c "
import json; f=json.load(open('$fam/family.json'))
assert f['format']=='skinbake-family' and f['format_version']==1
ax=f['axes']; assert [a['key'] for a in ax]==['epidermis.melanin','dermis.blood']
assert ax[0]['nodes']==[0.01,0.2] and ax[0]['spacing']=='log' and ax[1]['spacing']=='list' and ax[1]['log_coordinate']
m=f['members']; assert len(m)==4 and m[1]['params']==[0.2,0.01] and m[2]['params']==[0.01,0.06]
for k in m:
    mm=json.load(open('$fam/'+k['dir']+'/manifest.json'))
    assert [j['albedo'] for j in mm['jobs']]==k['albedo_wl'], k['dir']
    assert mm['radial']['mean_radius_rgb_cm']==k['sss_radius_rgb_cm']
# more melanin darkens, more blood reddens (a* up)
assert m[1]['albedo_lab'][0] < m[0]['albedo_lab'][0] - 5 and m[2]['albedo_lab'][1] > m[0]['albedo_lab'][1] + 3"
# A member is the plain bake of its parameters (same seed, same tables).
awk '/^\[/ { s = $0 } s == "[epidermis]" && /^melanin =/ { $0 = "melanin = 0.2" }
	s == "[dermis]" && /^blood =/ { $0 = "blood = 0.06" } { print }' "$fam/preset.ini" > "$tmpd/m3.ini"
check "plain bake of member 3's preset" "$B" bake --preset-file "$tmpd/m3.ini" $small --out "$tmpd/m3" --quiet
for d in "$fam/m0003" "$tmpd/m3"; do
	for a in "0 0 0" "0 50 180" "0 80 90"; do
		set -- $a
		"$B" eval --bake "$d" --theta-in $1 --theta-out $2 --phi $3 --json
	done > "$d.eval"
	python3 -c "import json; print(json.load(open('$d/manifest.json'))['jobs'])" >> "$d.eval"
done
check "member m0003 has the plain bake's table" cmp "$fam/m0003.eval" "$tmpd/m3.eval"
check "members record the solver as the plain bake does (ad)" python3 -c "
import json; f=json.load(open('$fam/family.json')); a=json.load(open('$fam/m0003/manifest.json'))
b=json.load(open('$tmpd/m3/manifest.json'))
assert f['bake']['solver']=='ad' and a['solver']==b['solver'] and a['solver']['name']=='ad', (f['bake'], a['solver'])
assert [j['solver'] for j in a['jobs']]==['ad']*4 and [j.get('n_quad') for j in a['jobs']]==[j.get('n_quad') for j in b['jobs']]
# Rd(r): the member's from the family's shared white Monte Carlo run, the
# plain bake's from its own run; the same quantity within their errors.
ra, rb = a['radial'], b['radial']
assert ra['method'].startswith('white Monte Carlo') and rb['method'].startswith('Monte Carlo'), ra['method']
assert len(ra['rd_r'][0])==len(rb['rd_r'][0]) and ra['target_rel_err']==rb['target_rel_err']
for x, ex, y, ey in zip(ra['mean_radius_cm'], ra['mean_radius_err_cm'], rb['mean_radius_cm'], rb['mean_radius_err_cm']):
    assert abs(x - y) <= 4 * (ex * ex + ey * ey) ** 0.5, (x, ex, y, ey)"
# Monte Carlo members: the packed result (photons, batches, method) survives the gather.
check "Monte Carlo family" "$B" bake --preset fair-oily $small --solver mc --vary dermis.blood=0.01,0.06 \
	--out "$tmpd/fmc" --quiet --threads 2
awk '/^\[/ { s = $0 } s == "[dermis]" && /^blood =/ { $0 = "blood = 0.06" } { print }' "$fam/preset.ini" > "$tmpd/mc1.ini"
check "plain Monte Carlo bake of its member 1" "$B" bake --preset-file "$tmpd/mc1.ini" $small --solver mc \
	--out "$tmpd/mc1" --quiet
check "Monte Carlo member m0001 = the plain bake (jobs, solver, radial)" python3 -c "
import json; a=json.load(open('$tmpd/fmc/m0001/manifest.json')); b=json.load(open('$tmpd/mc1/manifest.json'))
assert a['jobs']==b['jobs'] and a['solver']==b['solver'] and a['solver']['name']=='mc'
assert {k: v for k, v in a['radial'].items() if k!='seconds'}=={k: v for k, v in b['radial'].items() if k!='seconds'}"
for d in "$tmpd/fmc/m0001" "$tmpd/mc1"; do
	"$B" eval --bake "$d" --theta-in 0 --theta-out 50 --phi 180 --json > "$d.eval"
done
check "Monte Carlo member m0001 has the plain bake's fr" cmp "$tmpd/fmc/m0001.eval" "$tmpd/mc1.eval"
if command -v mpirun >/dev/null 2>&1 && [ -x "$top_builddir/skinbake-mpi" ]; then
	check "the family over 2 MPI ranks" mpirun --allow-run-as-root -np 2 "$top_builddir/skinbake-mpi" bake \
		--preset fair-oily $small --vary epidermis.melanin=0.01:0.2:2:log --vary dermis.blood=0.01,0.06 \
		--out "$tmpd/fam2" --quiet --threads 1
	same=yes
	for m in m0000 m0001 m0002 m0003; do
		for f in brdf.exr brdf_rgb.exr albedo.exr; do cmp -s "$fam/$m/$f" "$tmpd/fam2/$m/$f" || same=no; done
	done
	check "member tables bit-identical over 1 and 2 ranks" [ $same = yes ]
	grep -v -e seconds -e command -e checksums "$fam/family.json" > "$tmpd/j1"
	grep -v -e seconds -e command -e checksums "$tmpd/fam2/family.json" > "$tmpd/j2"
	check "family.json identical but for times, the command and the checksums (of member manifests with times)" cmp "$tmpd/j1" "$tmpd/j2"
else
	skip "skinbake-mpi or mpirun missing (configure --with-mpi)"
fi
# Replacing an earlier family is allowed.
check "a family replaces an earlier family" "$B" bake --preset fair-oily $small --vary dermis.blood=0.01,0.06 \
	--out "$fam" --quiet
check "the replaced family has the new members only" sh -c "[ -d '$fam/m0001' ] && [ ! -d '$fam/m0002' ]"

bad() {	# DESC PATTERN ARGS...: skinbake ARGS refused (tests/lib/refused.sh)
	b_d=$1 b_p=$2
	shift 2
	refused "$b_d" "$b_p" "$tmpd/bad $tmpd/bad.staging" "$B" "$@"
}
bad "unknown key" "'epidermis.colour' is not a numeric preset key (one of" bake --preset fair-oily \
	--vary epidermis.colour=0:1:3 --out "$tmpd/bad"
bad "value outside the key's range" "dermis.blood: 0.01:0.5 is outside the key's range \[0, 0.2\]" bake \
	--preset fair-oily --vary dermis.blood=0.01:0.5:3 --out "$tmpd/bad"
bad "log from 0" "log spacing needs a start > 0" bake --preset fair-oily --vary dermis.blood=0:0.1:3:log \
	--out "$tmpd/bad"
bad "bad spacing" "spacing 'cubic' is not one of de, log, lin" bake --preset fair-oily \
	--vary dermis.blood=0.01:0.1:3:cubic --out "$tmpd/bad"
bad "one node" "N = 1 is out of range \[2, 64\]" bake --preset fair-oily --vary dermis.blood=0.01:0.1:1 --out "$tmpd/bad"
bad "hex number" "--vary dermis.blood" bake --preset fair-oily --vary dermis.blood=0x1:0.1:3 --out "$tmpd/bad"
bad "same key twice" "given twice" bake --preset fair-oily --vary dermis.blood=0.01:0.1:3 \
	--vary dermis.blood=0.01:0.1:3 --out "$tmpd/bad"
bad "four axes" "at most 3" bake --preset fair-oily --vary dermis.blood=0.01:0.1:2 --vary dermis.so2=0.5:0.9:2 \
	--vary epidermis.melanin=0.01:0.1:2 --vary sebum.thickness=0:0.001:2 --out "$tmpd/bad"
bad "too many members" "larger than 4096" bake --preset fair-oily $small --vary dermis.blood=0.01:0.1:64:lin \
	--vary dermis.so2=0.5:0.9:64:lin --vary epidermis.melanin=0.01:0.1:2:lin --out "$tmpd/bad"
mkdir -p "$tmpd/other" && echo keep > "$tmpd/other/notes.txt"
msg=$("$B" bake --preset fair-oily $small --vary dermis.blood=0.01,0.06 --out "$tmpd/other" 2>&1 >/dev/null)
rc=$?
check "a non-family directory is refused (exit 2), its file kept" sh -c "[ $rc = 2 ] && [ -f '$tmpd/other/notes.txt' ] \
	&& echo '$msg' | grep -q 'without family.json, not a family directory'"
tap_done
