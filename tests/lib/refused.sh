# The shell tests' check of refused input (sourced after tests/tap.sh): skinbake's promise that
# bad input gets exit status 2, a message naming the field, value and range, and no output.
#   refused DESC PATTERN OUTPUTS CMD...
#       runs CMD (OUTPUTS, a space-separated list of paths or glob patterns, removed first); ok
#       when it exits 2, its standard error matches PATTERN and none of OUTPUTS exists
#       afterwards.  Else not ok with the exit status, what was left and the start of the
#       message.  The message is in $tmpd/refused.err, its first line in $refused_msg.
# PATTERN is grep's basic regular expression, and what more is checked, is set by these
# variables (set them once at the top of a test, or in its wrapper before each call):
#   refused_ere=1       PATTERN is an extended regular expression (grep -E)
#   refused_fixed=1     PATTERN is one or more fixed strings joined by '|', each of which must
#                       be in the message (shell builtins only: no process but CMD per call)
#   refused_quiet=1     nothing on standard output
#   refused_one_line=1  exactly one line on standard error
#   refused_prefix=GLOB the first line of the message starts with what the shell pattern GLOB
#                       matches (e.g. "skinbake bake[ :]")
#   refused_kept=PATHS  each of these files or directories holds after the run what it held
#                       before (a file is read with the shell's read, a directory by cksum)
# Without refused_ere and refused_fixed a call runs two processes besides CMD (grep, head);
# with refused_fixed none, for tests that make hundreds of calls.

# refused_snapshot PATH: PATH's content as one string (a directory: each file's cksum).
refused_snapshot() {
	if [ -d "$1" ]; then
		(cd "$1" && find . -type f | LC_ALL=C sort | while read -r f; do cksum "$f"; done) 2>/dev/null
		return
	fi
	[ -e "$1" ] || { echo "(absent)"; return; }
	r_s=
	while IFS= read -r r_l || [ -n "$r_l" ]; do
		r_s="$r_s$r_l
"
	done <"$1"
	printf '%s' "$r_s"
}

# refused_has MESSAGE NEEDLES: the needles ('|'-joined fixed strings) that MESSAGE lacks,
# each as " 'NEEDLE'".
refused_has() {
	r_m=$1 r_miss=
	r_ifs=$IFS
	IFS='|'
	set -f	# needles like "[1, 10]" are not file patterns
	for r_n in $2; do
		case $r_m in *"$r_n"*) ;; *) r_miss="$r_miss '$r_n'" ;; esac
	done
	set +f
	IFS=$r_ifs
	printf '%s' "$r_miss"
}

refused() {
	r_desc=$1 r_pat=$2 r_outs=$3
	shift 3
	for r_f in $r_outs; do
		if [ -e "$r_f" ] || [ -L "$r_f" ]; then
			rm -rf "$r_f"
		fi
	done
	r_keep=
	for r_f in $refused_kept; do
		r_keep="$r_keep$(refused_snapshot "$r_f")|"
	done
	"$@" >"$tmpd/refused.out" 2>"$tmpd/refused.err"
	r_rc=$?
	r_why=
	[ "$r_rc" -eq 2 ] || r_why=" exit $r_rc"
	# The message: its first line, its line count and (for fixed strings) its whole text.
	refused_msg= r_lines=0 r_all=
	while IFS= read -r r_l || [ -n "$r_l" ]; do
		r_lines=$((r_lines + 1))
		[ "$r_lines" -eq 1 ] && refused_msg=$r_l
		r_all="$r_all$r_l
"
	done <"$tmpd/refused.err"
	if [ -n "$refused_fixed" ]; then
		r_miss=$(refused_has "$r_all" "$r_pat")
		[ -z "$r_miss" ] || r_why="$r_why, no$r_miss"
	else
		grep -q${refused_ere:+E} -- "$r_pat" "$tmpd/refused.err" || r_why="$r_why, no '$r_pat'"
	fi
	[ -z "$refused_one_line" ] || [ "$r_lines" -eq 1 ] || r_why="$r_why, $r_lines lines on stderr"
	if [ -n "$refused_prefix" ]; then
		# shellcheck disable=SC2254
		case $refused_msg in $refused_prefix*) ;; *) r_why="$r_why, no '$refused_prefix' prefix" ;; esac
	fi
	for r_f in $r_outs; do
		if [ -e "$r_f" ] || [ -L "$r_f" ]; then
			r_why="$r_why, left $r_f"
		fi
	done
	[ -z "$refused_quiet" ] || [ ! -s "$tmpd/refused.out" ] || r_why="$r_why, wrote stdout"
	r_after=
	for r_f in $refused_kept; do
		r_after="$r_after$(refused_snapshot "$r_f")|"
	done
	[ "$r_keep" = "$r_after" ] || r_why="$r_why, changed one of $refused_kept"
	if [ -z "$r_why" ]; then
		ok "$r_desc: $refused_msg"
	else
		fail "$r_desc:$r_why: $(printf '%s' "$r_all" | head -c 300)"
	fi
}
