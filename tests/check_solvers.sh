#!/bin/sh
# The solver registry (engine/solvers.h): a method is its own file and one
# line of solvers[]; nothing else under src/ names it.  For each method (the
# `.name = "X"` of a `struct solver_ops`), a string literal "X", "X+..." or
# "...+X" outside the methods' files and the table fails, comments aside.
# Then probes: a planted name is caught, one in comments is not.
. "$top_srcdir/tests/tap.sh"
cd "$top_srcdir/src" || exit 1
# names: "FILE NAME" for each method defined under DIR.
names() {
	grep -l 'const struct solver_ops [a-z_]* = {' "$1"/*/*.c 2>/dev/null | while read -r f; do
		sed -n 's/^[ \t]*\.name = "\([^"]*\)",.*/\1/p' "$f" | sed "s|^|$f |"
	done
}
# named DIR NAME: lines under DIR naming NAME as a string literal, outside the
# methods' files and the table, with comments taken out of each line first.
named() {
	skip=$(names "$1" | sed 's/ .*//' | sort -u | tr '\n' '|')
	grep -rn --include='*.[ch]' -F "$2" "$1" | grep -vE "^(${skip}$1/engine/solvers\.c):" |
		sed -E 's#/\*.*\*/##g; s#/\*.*$##; s#//.*$##; s#^([^:]*:[0-9]+:)[ \t]*\*.*#\1#' |
		grep -E "\"($2|$2\+[a-z+]*|[a-z+]*\+$2)\""
}
n=0
for pair in $(names . | tr ' ' '='); do
	f=${pair%%=*} m=${pair#*=}
	n=$((n + 1))
	hits=$(named . "$m")
	if [ -z "$hits" ]; then ok "method \"$m\" ($f) is named nowhere else"; else fail "method \"$m\" named outside its file and the table: $(echo "$hits" | tr '\n' ' ')"; fi
done
check "the table lists the methods found ($n)" test "$n" -ge 2 -a "$n" = "$(grep -c '^	&[a-z_]*,$' engine/solvers.c)"
# Probes on a copy: a planted name in bake.c is caught, in a comment it is not.
mkdir -p "$tmpd/src/engine" "$tmpd/src/bake"
cp engine/solvers.c engine/mc.c engine/ad_solver.c "$tmpd/src/engine/"
m=$(names . | sed -n '1s/.* //p')
printf 'static const char *x = "%s";\n' "$m" > "$tmpd/src/bake/p.c"
check "a probe naming \"$m\" in bake/ is caught" test -n "$(cd "$tmpd/src" && named . "$m")"
printf 'static const char *x = "x+%s";\n' "$m" > "$tmpd/src/bake/p.c"
check "a probe naming \"x+$m\" is caught" test -n "$(cd "$tmpd/src" && named . "$m")"
printf 'int x; /* the method "%s" */\n/* more\n * "%s"\n */\n' "$m" "$m" > "$tmpd/src/bake/p.c"
check "the same name in a comment is not" test -z "$(cd "$tmpd/src" && named . "$m")"
tap_done
