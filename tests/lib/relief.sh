# Relief helpers of the shell tests (sourced after tests/tap.sh):
#   relief_bake          a small, fast paper bake in $tmpd/bake (6 theta nodes, 9 x 9, 3e5 photons
#                        at most); fails the test and exits when the bake fails
#   relief_textures SIZE the face site's relief and a flat one (no furrow levels, pores or plateau
#                        roughness) of SIZE px over an 8 mm tile, in $tmpd/tex-face and
#                        $tmpd/tex-flat; one check
relief_bake() {
	bake="$tmpd/bake"
	if ! "$SKINBAKE" bake --preset paper --out "$bake" --theta-nodes 6 --resolution 9x9 --batch-photons 1000 \
		--max-photons 3e5 --target-error 0 --threads 1 --quiet >"$tmpd/bake.log" 2>&1; then
		fail "skinbake bake failed: $(tail -2 "$tmpd/bake.log")"
		tap_done
		exit 1
	fi
}
relief_textures() {
	"$SKINBAKE" texture --site face --size "$1" --tile-mm 8 --quiet --out "$tmpd/tex-face" &&
	"$SKINBAKE" texture --site face --size "$1" --tile-mm 8 --levels 0 --pore-density 0 \
		--plateau-roughness 0 --quiet --out "$tmpd/tex-flat"
	check "face and flat textures" test $? -eq 0
}
