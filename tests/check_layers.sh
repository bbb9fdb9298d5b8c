#!/bin/sh
# The layer rule: a file under src/ includes only headers of its own folder or
# of folders of a lower layer (the table below, lowest first), and names every
# project header by its folder ("engine/slab.h").  One TAP line per file.
. "$top_srcdir/tests/tap.sh"
rank() {
	case $1 in
	base) echo 0 ;; io) echo 1 ;; engine) echo 2 ;; skin | geom) echo 3 ;; bake) echo 4 ;;
	export | maps | scene) echo 5 ;; export/pov | export/blender) echo 6 ;; cli) echo 7 ;; *) echo -1 ;;
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
# The rule itself: upward, sideways and folderless includes are caught.
printf '#include "cli/cli.h"\n' > "$tmpd/up.c"
printf '#include "geom/relief.h"\n' > "$tmpd/side.c"
printf '#include "slab.h"\n' > "$tmpd/flat.c"
for t in up side flat; do
	check "a probe with a wrong include ($t) is caught" test -n "$(violations "$tmpd/$t.c" skin)"
done
tap_done
