#!/bin/sh
# The MPI bake under mpirun -np 2 writes tables bit-identical to the
# single-process bake with the same seed.
. "$top_srcdir/tests/tap.sh"
MPI="$top_builddir/skinbake-mpi"
args="--preset paper --theta-in 0,40 --resolution 6x4 --target-error 0.2 --batch-photons 500 --seed 7 --quiet"
check "single-process bake" "$SKINBAKE" bake $args --out "$tmpd/one" --threads 2
if command -v mpirun >/dev/null 2>&1; then
	check "mpirun -np 2 bake" mpirun --allow-run-as-root -np 2 "$MPI" bake $args --out "$tmpd/two" --threads 1
	for f in brdf.exr brdf_rgb.exr albedo.exr; do
		check "$f bit-identical over 1 and 2 ranks" cmp "$tmpd/one/$f" "$tmpd/two/$f"
	done
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
