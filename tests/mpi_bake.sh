#!/bin/sh
# The MPI bake under mpirun -np 2 writes tables bit-identical to the
# single-process bake with the same seed: Monte Carlo with fixed batches and
# with batches sized from the target, and adding-doubling (every rank solves
# the table; its Rd(r) run is split over the ranks).
. "$top_srcdir/tests/tap.sh"
MPI="$top_builddir/skinbake-mpi"
args="--preset paper --theta-in 0,40 --resolution 6x4 --target-error 0.2 --seed 7 --quiet"
check "single-process bake" "$SKINBAKE" bake $args --solver mc --batch-photons 500 --out "$tmpd/one" --threads 2
check "single-process bake, sized batches" "$SKINBAKE" bake $args --solver mc --out "$tmpd/one-s" --threads 2
check "single-process bake, adding-doubling" "$SKINBAKE" bake $args --solver ad --radial-photons 2000 --out "$tmpd/one-ad" --threads 2
if command -v mpirun >/dev/null 2>&1; then
	check "mpirun -np 2 bake" mpirun --allow-run-as-root -np 2 "$MPI" bake $args --solver mc --batch-photons 500 --out "$tmpd/two" --threads 1
	check "mpirun -np 2 bake, sized batches" mpirun --allow-run-as-root -np 2 "$MPI" bake $args --solver mc --out "$tmpd/two-s" --threads 1
	check "mpirun -np 2 bake, adding-doubling" mpirun --allow-run-as-root -np 2 "$MPI" bake $args --solver ad --radial-photons 2000 --out "$tmpd/two-ad" --threads 1
	for f in brdf.exr brdf_rgb.exr albedo.exr; do
		check "$f bit-identical over 1 and 2 ranks" cmp "$tmpd/one/$f" "$tmpd/two/$f"
		check "$f bit-identical over 1 and 2 ranks, sized batches" cmp "$tmpd/one-s/$f" "$tmpd/two-s/$f"
		check "$f bit-identical over 1 and 2 ranks, adding-doubling" cmp "$tmpd/one-ad/$f" "$tmpd/two-ad/$f"
	done
	check "adding-doubling: the same subsurface radii over 1 and 2 ranks" python3 -c "
import json; a, b = (json.load(open('$tmpd/%s/manifest.json' % d))['radial'] for d in ('one-ad', 'two-ad'))
assert a['mean_radius_cm'] == b['mean_radius_cm'] and a['rd_r'] == b['rd_r']"
	mpirun --allow-run-as-root -np 2 "$MPI" bake --preset no-such-preset --out "$tmpd/bad" >/dev/null 2>"$tmpd/bad.err"
	rc=$?
	check "bad preset under MPI exits 2" [ "$rc" = 2 ]
	check "bad preset under MPI: one rank prints the error" \
		[ "$(grep -c "^skinbake bake: .*no-such-preset" "$tmpd/bad.err")" = 1 ]
	check "bad preset under MPI writes nothing" [ ! -e "$tmpd/bad" ]
else
	fail "mpirun is missing (scripts/setup.sh installs openmpi-bin)"
fi
tap_done
