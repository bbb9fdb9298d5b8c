#!/bin/sh
# Probes of tests/lib/refused.sh, the shell tests' check of refused input: a
# refusal that keeps every promise passes, and each promise it checks
# (exit 2, the message by regular expression or fixed strings, one line,
# the command's prefix, nothing on stdout, no output left, a kept file
# unchanged) catches a planted breach.  No skinbake run: under 1 s.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
echo x >"$tmpd/file"
# Planted commands: each breaks one promise (good keeps them all).
good() { echo "skinbake bake: --x = 1 is out of range [0, 1)" >&2; return 2; }
exit1() { good; return 1; }
kept() { echo y >"$tmpd/file"; good; }
two() { good; echo "and more" >&2; return 2; }
out() { echo hi; good; }
left() { mkdir -p "$tmpd/new1"; good; }
# probe DESC WANT CMD...: refused's verdict on CMD (in a subshell, its TAP line
# kept) is WANT (ok or not).
probe() {
	p_d=$1 p_w=$2
	shift 2
	p_l=$( (tap_n=0; refused "$p_d" "$@") 2>&1 | head -n 1)
	case $p_l in
	"$p_w "*) ok "$p_d: refused says $p_w" ;;
	*) fail "$p_d: wanted '$p_w', got: $p_l" ;;
	esac
}
probe "grep BRE: a good refusal passes" ok "out of range \[0, 1)" "" good
probe "grep BRE: a message without the pattern" "not ok" "out of range \[0, 2)" "" good
refused_ere=1
probe "grep ERE: alternatives" ok "in range|out of range" "" good
refused_ere=
probe "exit 1 is not a refusal" "not ok" "out of range" "" exit1
refused_fixed=1
probe "fixed strings: all present" ok "[0, 1)|--x = 1" "" good
probe "fixed strings: one absent" "not ok" "[0, 1)|--y" "" good
refused_one_line=1
probe "one line: two lines" "not ok" "--x" "" two
refused_prefix="skinbake bake[ :]"
probe "prefix: the command's" ok "--x" "" good
refused_prefix="skinbake eval[ :]"
probe "prefix: another command's" "not ok" "--x" "" good
refused_prefix=
refused_quiet=1
probe "quiet: output on stdout" "not ok" "--x" "" out
probe "outputs: a directory left (glob)" "not ok" "--x" "$tmpd/new*" left
probe "outputs: removed before the run" ok "--x" "$tmpd/new*" good
refused_kept=$tmpd/file
probe "kept: a file changed" "not ok" "--x" "" kept
probe "kept: a file unchanged" ok "--x" "" good
tap_done
