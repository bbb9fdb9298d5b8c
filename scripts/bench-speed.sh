#!/bin/sh
# Speed benchmarks (issue 28), in CPU seconds (user + system): the machine is shared, so wall
# times say little.  Each figure is the smallest CPU time of REPS runs (default 3).
#   1. One adding-doubling solve (one slab, normal incidence, the m = 0 order only) against Scott
#      Prahl's `ad` (iad) at equal accuracy, both against the converged answer.  iad is built
#      with -O2 from its public source when IAD_SRC names a checkout of github.com/scottprahl/iad
#      (its code never enters this repository; scripts/iad_time.c calls its ez_RT); without it,
#      that part is skipped.  The whole `simulate --solver ad` command against `ad`'s command.
#   2. `bake --preset paper` and the 16-wavelength presets by adding-doubling, with the share of
#      the Rd(r) Monte Carlo run (the same bake with --radial-photons 100 --radial-error 1, and
#      the manifest's radial.seconds); with BASE_SKINBAKE, the full bakes against the older binary.
#   3. A small family (the two 17-point pilots and 4 members); with BASE_SKINBAKE, it (and with
#      BENCH_FAMILY86=1 the 8 x 6 family) against the older binary: Rd(r) shared by white Monte Carlo.
#   4. With BASE_SKINBAKE (an older binary) and valgrind: instructions (callgrind, independent of
#      the load) of the old and this binary on the same commands.
# Prints one markdown section.  Builds tests/ad_bench when it is missing.
set -eu
SKINBAKE=${SKINBAKE:-./skinbake}
top_builddir=${top_builddir:-.}
top_srcdir=${top_srcdir:-.}
REPS=${REPS:-3}
ADB="$top_builddir/tests/ad_bench"
[ -x "$ADB" ] || make -C "$top_builddir" tests/ad_bench >/dev/null
W=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench-speed.XXXXXX")
trap 'rm -rf "$W"' EXIT INT TERM

. "$(dirname "$0")/bench-lib.sh"
# field KEY LINE: the value after KEY in a "key value key value" line
field() { echo "$2" | awk -v k="$1" '{ for (i = 1; i < NF; i++) if ($i == k) print $(i + 1) }'; }

echo "## Speed (CPU seconds)"
echo
echo "Machine: $(nproc) cores, $(date -u +%Y-%m-%d), load average $(cut -d' ' -f1-3 /proc/loadavg) at the start."
echo "Command: \`make bench\` (scripts/bench-speed.sh; \`IAD_SRC=DIR\` for the comparison with iad)."
echo "Every time is the smallest CPU time (user + system) of $REPS runs."
echo

# ---- 1. one solve against Prahl's ad ----
SLAB="0.9 10 0.9 1.4"
echo "### One adding-doubling solve against Prahl's \`ad\`"
echo
echo "Slab: albedo 0.9, optical thickness 10, g 0.9, index 1.4 in air, normal incidence, m = 0 only."
echo "Errors against skinbake at 64 nodes per unit cosine (R = specular + diffuse reflectance, T = total"
echo "transmittance, as \`ad\` reports UR1 and UT1). skinbake's time per solve is given without and with its"
echo "error estimate (the second solve at half the nodes; iad has none)."
echo
ref=$(OMP_NUM_THREADS=1 "$ADB" --slab "0.9,10,0.9,1.4,64,2" | awk '$4 == 0')
R0=$(field R "$ref")
T0=$(field T "$ref")
echo "| code | nodes per hemisphere | R | T | error R | error T | ms per solve | ms with estimate |"
echo "|---|---|---|---|---|---|---|---|"
# minms FILE EST: the line of FILE (estimate EST for ad_bench) with the smallest ms per solve
minms() { awk -v e="$2" '(e == "" || $4 == e) && (best == "" || $NF < m) { m = $NF; best = $0 } END { print best }' "$1"; }
for q in 16 18 32; do
	: >"$W/sb"
	i=0
	while [ $i -lt "$REPS" ]; do
		OMP_NUM_THREADS=1 "$ADB" --slab "0.9,10,0.9,1.4,$q,200" >>"$W/sb"
		i=$((i + 1))
	done
	a=$(minms "$W/sb" 0)
	b=$(minms "$W/sb" 1)
	echo "$a $b" | awk -v r0="$R0" -v t0="$T0" -v q="$q" '{ printf "| skinbake --ad-quad %d | %d | %.8f | %.8f | %.1e | %.1e | %.3f | %.3f |\n",
	    q, $14, $6, $8, ($6 > r0 ? $6 - r0 : r0 - $6), ($8 > t0 ? $8 - t0 : t0 - $8), $18, $36 }'
	eval "SB_$q=\$(field ms_per_solve \"\$a\")"
done
IAD_MS=
if [ -n "${IAD_SRC:-}" ] && [ -f "$IAD_SRC/src/ad_prime.c" ]; then
	# Compiled file by file (its Makefile would rerun ctangle on a copy).
	mkdir "$W/iad"
	printf 'char *Version = "iad";\nchar *VersionShort = "iad";\n' >"$W/iad/version.c"
	for f in ad_bound ad_doubl ad_frsnl ad_globl ad_matrx ad_phase ad_prime ad_radau ad_start ad_cone \
		ad_layers nr_zbrak nr_amoeb nr_amotr nr_brent nr_gaulg nr_mnbrk nr_rtsaf nr_util nr_hj nr_zbrent; do
		cc -O2 -fno-common -fsigned-char -DNDEBUG -I"$IAD_SRC/src" -c "$IAD_SRC/src/$f.c" -o "$W/iad/$f.o"
	done
	cc -O2 -c "$W/iad/version.c" -o "$W/iad/version.o"
	cc -O2 -fno-common -fsigned-char -DNDEBUG -I"$IAD_SRC/src" -o "$W/iad/ad" "$IAD_SRC/src/ad_main.c" \
		"$W"/iad/*.o -lm
	cc -O2 -o "$W/iad/iad_time" "$top_srcdir/scripts/iad_time.c" "$W"/iad/*.o -lm
	for q in 16 32 64; do
		: >"$W/it"
		i=0
		while [ $i -lt "$REPS" ]; do
			"$W/iad/iad_time" $SLAB $q 200 >>"$W/it"
			i=$((i + 1))
		done
		l=$(minms "$W/it" "")
		echo "$l" | awk -v r0="$R0" -v t0="$T0" -v q="$q" '{ printf "| iad ad -q %d | %d | %.8f | %.8f | %.1e | %.1e | %.3f | - |\n",
		    q, q, $4, $6, ($4 > r0 ? $4 - r0 : r0 - $4), ($6 > t0 ? $6 - t0 : t0 - $6), $8 }'
		[ "$q" = 32 ] && IAD_MS=$(field ms_per_solve "$l")
	done
	echo
	echo "At equal accuracy (skinbake at 18 nodes per unit cosine is at least as accurate as iad at 32"
	echo "quadrature points in both R and T): iad $IAD_MS ms, skinbake $SB_18 ms per solve:"
	echo "**$(awk -v a="$IAD_MS" -v b="$SB_18" 'BEGIN { printf "%.2f", a / b }') x** faster (goal >= 2)."
	echo
	SIM="$SKINBAKE simulate --layer d=1,n=1.4,mua=1,mus=9,g=0.9 --solver ad --ad-quad 18 --threads 1"
	c_sb=$(cpu sh -c "for i in 1 2 3 4 5 6 7 8 9 10; do $SIM; done")
	c_ad=$(cpu sh -c "for i in 1 2 3 4 5 6 7 8 9 10; do $W/iad/ad -a 0.9 -b 10 -g 0.9 -n 1.4 -q 32; done")
	c_v=$(cpu sh -c "for i in 1 2 3 4 5 6 7 8 9 10; do $SKINBAKE --version; done")
	echo "Whole commands (10 runs each, CPU per run): \`$SIM\` (all Fourier orders, 18 x 36 bins)"
	echo "$(awk -v a="$c_sb" 'BEGIN { printf "%.1f", a * 100 }') ms; \`ad -a 0.9 -b 10 -g 0.9 -n 1.4 -q 32\`"
	echo "$(awk -v a="$c_ad" 'BEGIN { printf "%.1f", a * 100 }') ms; \`skinbake --version\` (start-up alone)"
	echo "$(awk -v a="$c_v" 'BEGIN { printf "%.1f", a * 100 }') ms."
else
	echo
	echo "(iad not built: set IAD_SRC to a checkout of github.com/scottprahl/iad.)"
fi
echo

# ---- 2. bakes ----
echo "### Bakes by adding-doubling"
echo
echo "\`skinbake bake --preset NAME --solver ad --threads 1 --out DIR --quiet\`; \"no Rd(r)\" adds"
echo "\`--radial-photons 100 --radial-error 1\` (the radial Monte Carlo run at its minimum; it still"
echo "makes the controls' means, one m = 0 adding-doubling solve per wavelength, bake/radial.h), so the"
echo "difference is the Rd(r) run's Monte Carlo CPU time.  \"Rd(r) wall share\" is the manifest's"
echo "radial.seconds over the bake's wall time in the full run (one thread, controls included)."
echo "\"estimated\" is the table's RMS error estimate; \"photons\" the Rd(r) run's (target 2 % on the"
echo "mean radius)."
echo
echo "| preset | CPU [s] | CPU no Rd(r) [s] | Rd(r) share | Rd(r) wall share | Rd(r) photons | estimated |"
echo "|---|---|---|---|---|---|---|"
for p in ${BENCH_PRESETS:-paper fair-oily dark-dry}; do
	full=$(cpu "$SKINBAKE" bake --preset "$p" --solver ad --threads 1 --out "$W/b" --quiet)
	t0=$(date +%s.%N)
	"$SKINBAKE" bake --preset "$p" --solver ad --threads 1 --out "$W/b" --quiet
	t1=$(date +%s.%N)
	rad=$(python3 -c "import json; r = json.load(open('$W/b/manifest.json'))['radial']
print(r['photons'], '%.0f' % (100 * r['seconds'] / ($t1 - $t0)))")
	bare=$(cpu "$SKINBAKE" bake --preset "$p" --solver ad --threads 1 --out "$W/b" --quiet \
		--radial-photons 100 --radial-error 1)
	est=$(python3 -c "import json; print('%.3g' % json.load(open('$W/b/manifest.json'))['result']['rms_rel_err'])")
	share=$(awk -v a="$full" -v b="$bare" 'BEGIN { printf "%.0f %%", (a > 0 ? 100 * (a - b) / a : 0) }')
	echo "| $p | $full | $bare | $share | ${rad#* } % | ${rad% *} | $est |"
done
if [ -n "${BASE_SKINBAKE:-}" ]; then
	echo
	echo "The same full bakes by the older binary (\`$(basename "$BASE_SKINBAKE")\`), one after the other:"
	echo
	echo "| preset | old CPU [s] | new CPU [s] | new / old | old Rd(r) photons | new Rd(r) photons |"
	echo "|---|---|---|---|---|---|"
	for p in ${BENCH_PRESETS:-paper fair-oily dark-dry}; do
		o=$(cpu "$BASE_SKINBAKE" bake --preset "$p" --solver ad --threads 1 --out "$W/bo" --quiet)
		n=$(cpu "$SKINBAKE" bake --preset "$p" --solver ad --threads 1 --out "$W/bn" --quiet)
		po=$(python3 -c "import json; print(json.load(open('$W/bo/manifest.json'))['radial']['photons'])")
		pn=$(python3 -c "import json; print(json.load(open('$W/bn/manifest.json'))['radial']['photons'])")
		echo "| $p | $o | $n | $(awk -v a="$o" -v b="$n" 'BEGIN { printf "%.2f", b / a }') | $po | $pn |"
	done
fi
echo

# ---- 3. family ----
echo "### A small family"
echo
F="$SKINBAKE bake --preset fair-oily --vary epidermis.melanin=0.005:0.3:2 --vary dermis.blood=0.005:0.1:2 --threads 1 --quiet --out $W/f"
echo "\`$(echo "$F" | sed "s|$W/f|FAM|")\` (4 members and the two 17-point pilots): $(REPS=1 cpu $F) s CPU."
# The members' Rd(r) by white Monte Carlo shared per wavelength (family/family_radial.h) against
# the older binary's one run per member, one after the other; the 8 x 6 family with BENCH_FAMILY86=1.
if [ -n "${BASE_SKINBAKE:-}" ]; then
	echo
	echo "Rd(r) shared by the members (white Monte Carlo) against one run per member (\`$(basename "$BASE_SKINBAKE")\`,"
	echo "$("$BASE_SKINBAKE" --version 2>/dev/null | head -1)), CPU seconds measured one after the other:"
	echo
	echo "| family | old | new | new / old |"
	echo "|---|---|---|---|"
	for grid in 2:2 ${BENCH_FAMILY86:+8:6}; do
		G="bake --preset fair-oily --vary epidermis.melanin=0.005:0.3:${grid%:*} --vary dermis.blood=0.005:0.1:${grid#*:} --threads 1 --quiet"
		rm -rf "$W/fo" "$W/fn"
		o=$(REPS=1 cpu "$BASE_SKINBAKE" $G --out "$W/fo")
		n=$(REPS=1 cpu "$SKINBAKE" $G --out "$W/fn")
		echo "| \`skinbake $G --out FAM\` | $o | $n | $(awk -v a="$o" -v b="$n" 'BEGIN { printf "%.2f", b / a }') |"
	done
fi

# ---- 4. instructions against an older binary ----
if [ -n "${BASE_SKINBAKE:-}" ] && command -v valgrind >/dev/null 2>&1; then
	echo
	echo "### Instructions against an older binary"
	echo
	echo "Instructions executed (valgrind --tool=callgrind, one thread; unlike times, independent of the"
	echo "load), old binary: \`$(basename "$BASE_SKINBAKE")\` ($("$BASE_SKINBAKE" --version 2>/dev/null | head -1))."
	echo
	echo "| command | old | new | new / old | outputs |"
	echo "|---|---|---|---|---|"
	# ir BIN ARGS...: instructions of one run
	ir() {
		OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$W/cg" "$@" >/dev/null 2>"$W/vg" || true
		awk '/Collected :/ { print $NF }' "$W/vg"
	}
	row() {
		label=$1
		shift
		o=$(ir "$BASE_SKINBAKE" "$@" --out "$W/o1")
		n=$(ir "$SKINBAKE" "$@" --out "$W/o2")
		echo "| \`$label\` | $o | $n | $(awk -v a="$o" -v b="$n" 'BEGIN { printf "%.3f", b / a }') | $SAME |"
	}
	# What the outputs of the two binaries are known to share (BENCH_SAME_AD, BENCH_SAME: the
	# change under test's own check; the defaults are speed3's).
	SAME="${BENCH_SAME_AD:-AD values within 1.2e-8 relative (same-outputs.sh)}"
	row "bake --preset paper --solver ad --threads 1 --radial-photons 100 --radial-error 1" \
		bake --preset paper --solver ad --threads 1 --quiet --radial-photons 100 --radial-error 1
	SAME="${BENCH_SAME:-tables identical; Rd(r) within its stated error (tests/test_radial)}"
	row "bake --preset paper --solver ad --threads 1" bake --preset paper --solver ad --threads 1 --quiet
	row "bake --preset fair-oily --solver ad --threads 1" bake --preset fair-oily --solver ad --threads 1 --quiet
	"$top_builddir/tests/maps_check" synth "$W/f" "$W/true" 256 256 >/dev/null
	"$SKINBAKE" maps render-albedo --family "$W/f" --maps "$W/true" --out "$W/a.png" --quiet
	o=$(ir "$BASE_SKINBAKE" maps fit --family "$W/f" --albedo "$W/a.png" --out "$W/m1" --quiet --threads 1)
	n=$(ir "$SKINBAKE" maps fit --family "$W/f" --albedo "$W/a.png" --out "$W/m2" --quiet --threads 1)
	same=identical
	for f in "$W"/m2/*.png; do cmp -s "$f" "$W/m1/$(basename "$f")" || same=different; done
	echo "| \`maps fit --family FAM --albedo A.png --threads 1\` (256 x 256, FAM above) | $o | $n |" \
		"$(awk -v a="$o" -v b="$n" 'BEGIN { printf "%.3f", b / a }') | maps $same |"
fi

# ---- 5. what each pass did (hand-written notes with their own measurements, kept in
# docs/bench/bench-speed.history so that the generated tables above replace only themselves) ----
if [ -f "$top_srcdir/docs/bench/bench-speed.history" ]; then
	echo
	cat "$top_srcdir/docs/bench/bench-speed.history"
fi
