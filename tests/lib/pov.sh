# POV-Ray helpers of the shell tests (sourced after tests/tap.sh):
#   pov_require            fail the test, saying how to get it, when POV-Ray is missing
#   pov_render DIR BASE W H [POV options]
#                          DIR/BASE.pov -> DIR/r.png: 16-bit linear (File_Gamma=1.0), one ray per
#                          pixel through its centre (-A); fails, showing the message, on a
#                          POV-Ray error or warning (the log is DIR/pov.log)
pov_require() {
	if [ -z "$POVRAY" ] || ! command -v "$POVRAY" >/dev/null 2>&1; then
		fail "povray is missing (POVRAY='$POVRAY'): the project's set-up installs it (apt-get install povray), then re-run configure"
		tap_done
		exit 1
	fi
}
pov_render() {
	r_d=$1 r_b=$2 r_w=$3 r_h=$4
	shift 4
	(cd "$r_d" && "$POVRAY" "+I$r_b.pov" +Or.png "+W$r_w" "+H$r_h" -D -A +FN16 File_Gamma=1.0 "$@" >pov.log 2>&1) || {
		sed -n '/Parse Error/,+3p' "$r_d/pov.log" | head -5
		return 1
	}
	if grep -E "Error|Warning|Possible" "$r_d/pov.log" | grep -v "Stream to console" | grep -q .; then
		grep -E -A2 "Error|Warning|Possible" "$r_d/pov.log" | grep -v "Stream to console" | head -6
		return 1
	fi
}
