# Checkpoint helpers of the resume tests (sourced after tests/tap.sh):
#   ckpt_count DIR       the count a checkpoint DIR.checkpoint holds (solver runs of a bake,
#                        members of a family: its uint32 after the 23-byte header line and the
#                        8-byte identity), 0 without one
#   killat DIR N CMD...  start CMD, SIGKILL it once DIR.checkpoint holds N; 0 when it was
#                        killed that way, 1 when it ended first
#   resume_same REF DIR [KEY...]
#                        every file under REF equal in DIR, and no file more or less; *.json
#                        but their lines of "command", "seconds" and each KEY (wall times and
#                        the command line differ between an interrupted and a whole run)
ckpt_count() {
	n=$(od -An -tu4 -j31 -N4 "$1.checkpoint" 2>/dev/null | tr -d ' ')
	echo "${n:-0}"
}
killat() {
	kdir=$1 kn=$2
	shift 2
	"$@" & pid=$!
	while kill -0 $pid 2>/dev/null; do
		[ "$(ckpt_count "$kdir")" -ge "$kn" ] && break
		sleep 0.02
	done
	kill -9 $pid 2>/dev/null
	wait $pid
	[ $? -eq 137 ]
}
resume_same() {
	rs_ref=$1 rs_dir=$2
	shift 2
	printf '"%s":\n' command seconds "$@" > "$tmpd/same_keys"
	for f in $(cd "$rs_ref" && find . -type f | LC_ALL=C sort); do
		case $f in
		*.json) grep -v -F -f "$tmpd/same_keys" "$rs_ref/$f" > "$tmpd/same_a.json"
			grep -v -F -f "$tmpd/same_keys" "$rs_dir/$f" > "$tmpd/same_b.json"
			cmp -s "$tmpd/same_a.json" "$tmpd/same_b.json" || { echo "# $rs_dir/${f#./} differs"; return 1; } ;;
		*) cmp -s "$rs_ref/$f" "$rs_dir/$f" || { echo "# $rs_dir/${f#./} differs"; return 1; } ;;
		esac
	done
	[ "$(cd "$rs_ref" && find . | LC_ALL=C sort)" = "$(cd "$rs_dir" && find . | LC_ALL=C sort)" ]
}
