# The shell tests' check of refused input (sourced after tests/tap.sh): skinbake's promise that
# bad input gets exit status 2, a message naming the field, value and range, and no output.
#   refused DESC PATTERN OUTPUTS CMD...
#       runs CMD (OUTPUTS, a space-separated list of paths, removed first); ok when it exits 2,
#       its standard error matches PATTERN (grep's basic regular expression; with
#       refused_ere=1 extended) and none of OUTPUTS exists afterwards; with refused_quiet=1 its
#       standard output must also be empty.  Else not ok with the exit status, what was left
#       and the start of the message.  The message is in $tmpd/refused.err, its first line in
#       $refused_msg.
refused() {
	r_desc=$1 r_pat=$2 r_outs=$3
	shift 3
	for r_f in $r_outs; do
		rm -rf "$r_f"
	done
	"$@" >"$tmpd/refused.out" 2>"$tmpd/refused.err"
	r_rc=$?
	r_why=
	[ "$r_rc" -eq 2 ] || r_why=" exit $r_rc"
	grep -q${refused_ere:+E} -- "$r_pat" "$tmpd/refused.err" || r_why="$r_why, no '$r_pat'"
	for r_f in $r_outs; do
		[ -e "$r_f" ] && r_why="$r_why, left $r_f"
	done
	[ -z "$refused_quiet" ] || [ ! -s "$tmpd/refused.out" ] || r_why="$r_why, wrote stdout"
	refused_msg=$(head -n 1 "$tmpd/refused.err")
	if [ -z "$r_why" ]; then
		ok "$r_desc"
	else
		fail "$r_desc:$r_why: $(head -c 300 "$tmpd/refused.err")"
	fi
}
