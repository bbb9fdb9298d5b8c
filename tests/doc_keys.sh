#!/bin/sh
# The docs' tables of keys are the program's: README.md's table of preset keys is what
# scripts/doc_keys.py makes from `skinbake preset keys` (preset_key_table[]; `make doc-keys`
# rewrites it). A probe: the table with a row dropped is caught.
. "$top_srcdir/tests/tap.sh"
G="$top_srcdir/scripts/doc_keys.py"
check "README.md: the table of preset keys is the program's" python3 "$G" --check "$SKINBAKE" "$top_srcdir/README.md"
n=$("$SKINBAKE" preset keys | tail -n +2 | wc -l)
check "README.md lists all $n preset keys" test "$(sed -n '/<!-- preset keys:/,/<!-- end of preset keys/p' \
	"$top_srcdir/README.md" | grep -c '^| `')" -eq "$n"
grep -v '^| `dermis.blood` ' "$top_srcdir/README.md" >"$tmpd/README.md"
check "probe: a row dropped is caught" sh -c "! python3 '$G' --check '$SKINBAKE' '$tmpd/README.md' >/dev/null"
tap_done
