#!/bin/sh
# The layer rule: a file under src/ includes only headers of its own folder or
# of folders of a lower layer (the table below, lowest first), and names every
# project header by its folder ("engine/slab.h"); every exporter's folder
# (export/NAME) is one layer, so a new exporter needs no line here and
# exporters do not include each other.  One TAP line per file;
# then no include cycles between the files' modules, inside folders too.
. "$top_srcdir/tests/tap.sh"
rank() {
	case $1 in
	base) echo 0 ;; io) echo 1 ;; engine) echo 2 ;; skin | geom) echo 3 ;; bake) echo 4 ;; family) echo 5 ;;
	export | maps | scene) echo 6 ;; export/*) echo 7 ;; cli) echo 8 ;;
	*) echo -1 ;;
	esac
}
# violations FILE DIR: what FILE (taken to live in DIR) includes against the rule.
violations() {
	r=$(rank "$2")
	for inc in $(sed -n 's/^[ \t]*#[ \t]*include[ \t]*"\([^"]*\)".*/\1/p' "$1"); do
		[ "$inc" = config.h ] && continue
		idir=$(dirname "$inc")
		if [ "$idir" = . ] || [ ! -f "$inc" ]; then
			printf " '%s' is not a header named by its folder;" "$inc"
		elif [ "$idir" != "$2" ] && [ "$(rank "$idir")" -ge "$r" ]; then
			printf " includes %s (layer %s is not below %s);" "$inc" "$idir" "$2"
		fi
	done
}
cd "$top_srcdir/src" || exit 1
for f in $(find . -name '*.[ch]' | sed 's|^\./||' | LC_ALL=C sort); do
	dir=$(dirname "$f")
	if [ "$(rank "$dir")" -lt 0 ]; then fail "$f is not in a layer folder"; continue; fi
	why=$(violations "$f" "$dir")
	if [ -z "$why" ]; then ok "$f includes only its own and lower layers"; else fail "$f:$why"; fi
done
# No include cycles between modules, also inside a folder.  A module is a
# .c file with its .h; module X depends on Y when X.c or X.h includes Y.h
# (Y a module too: headers without a .c, shared types, are not nodes).
# KNOWN lists the dependencies of the cycles not yet broken, "Y X" as the
# edges below, each with its reason; remove a line when its cycle goes
# (none left: ad with ad_err went with engine/ad_types.h).
KNOWN=''
# edges DIR: "Y X" for each dependency of a module X on a module Y under DIR.
edges() {
	for f in $(cd "$1" && find . -name '*.[ch]' | sed 's|^\./||' | LC_ALL=C sort); do
		m=${f%.*}
		[ -f "$1/$m.c" ] || continue
		for inc in $(sed -n 's/^[ \t]*#[ \t]*include[ \t]*"\([^"]*\)".*/\1/p' "$1/$f"); do
			im=${inc%.h}
			if [ "$im" != "$m" ] && [ -f "$1/$im.c" ]; then echo "$im $m"; fi
		done
	done | LC_ALL=C sort -u
}
# cycles DIR: the modules of each include cycle under DIR (tsort's report), or nothing.
cycles() {
	edges "$1" | grep -vxF "$KNOWN" | tsort 2>&1 >/dev/null | sed -n 's/^tsort: \([^ :]*\)$/\1/p' | tr '\n' ' '
}
c=$(cycles .)
if [ -z "$c" ]; then ok "no include cycles between modules"; else fail "include cycles through: $c"; fi
mkdir -p "$tmpd/cyc/a"
printf '#include "a/y.h"\n' > "$tmpd/cyc/a/x.c"; : > "$tmpd/cyc/a/x.h"
printf '#include "a/x.h"\n' > "$tmpd/cyc/a/y.c"; : > "$tmpd/cyc/a/y.h"
check "a planted cycle inside a folder (x.c -> y.h, y.c -> x.h) is caught" test -n "$(cycles "$tmpd/cyc")"
rm "$tmpd/cyc/a/y.c"
check "the same without y.c (y.h only types) is no cycle" test -z "$(cycles "$tmpd/cyc")"
# The rule itself: upward, sideways and folderless includes are caught.
printf '#include "cli/cli.h"\n' > "$tmpd/up.c"
printf '#include "geom/relief.h"\n' > "$tmpd/side.c"
printf '#include "slab.h"\n' > "$tmpd/flat.c"
printf '#include "export/blender/blender.h"\n' > "$tmpd/sidex.c"
check "a probe with an exporter including another exporter is caught" \
	test -n "$(violations "$tmpd/sidex.c" export/pov)"
check "a new exporter's folder (export/new) is in the exporters' layer" test "$(rank export/new)" -eq 7
for t in up side flat; do
	check "a probe with a wrong include ($t) is caught" test -n "$(violations "$tmpd/$t.c" skin)"
done
tap_done
