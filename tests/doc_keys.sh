#!/bin/sh
# The docs' tables of keys are the program's: README.md's table of preset keys is what
# scripts/doc_keys.py makes from `skinbake preset keys` (preset_key_table[]; `make doc-keys`
# rewrites it); docs/presets.md's own table (its words, sources) has the same keys and the same
# numbers as units, defaults and ranges; scenes/README.md's key tables list the scene reader's
# keys and are generated from its key table (src/scene/scene_keytab.c, printed by
# tests/scene_keys_table). Probes: a row dropped, a default changed, a scene key missing or made
# up are caught.
. "$top_srcdir/tests/tap.sh"
G="$top_srcdir/scripts/doc_keys.py"
check "README.md: the table of preset keys is the program's" python3 "$G" --check "$SKINBAKE" "$top_srcdir/README.md"
n=$("$SKINBAKE" preset keys | tail -n +2 | wc -l)
check "README.md lists all $n preset keys" test "$(sed -n '/<!-- preset keys:/,/<!-- end of preset keys/p' \
	"$top_srcdir/README.md" | grep -c '^| `')" -eq "$n"
grep -v '^| `dermis.blood` ' "$top_srcdir/README.md" >"$tmpd/README.md"
check "probe: a row dropped is caught" sh -c "! python3 '$G' --check '$SKINBAKE' '$tmpd/README.md' >/dev/null"
check "docs/presets.md: keys, units, defaults and ranges are the program's" \
	python3 "$G" --check-values "$SKINBAKE" "$top_srcdir/docs/presets.md"
sed 's/^| `dermis.blood` | - | 0.02 |/| `dermis.blood` | - | 0.03 |/' "$top_srcdir/docs/presets.md" >"$tmpd/presets.md"
check "probe: a default changed in docs/presets.md is caught" \
	sh -c "! python3 '$G' --check-values '$SKINBAKE' '$tmpd/presets.md' >/dev/null"
# scenes/README.md: each section's table lists the keys the scene reader takes (its message for
# an unknown key names them; each is accepted), no more, no fewer.
check "scenes/README.md: every section's keys are the scene reader's" \
	python3 "$G" --check-scene-keys "$SKINBAKE" "$top_srcdir/scenes/README.md"
grep -v '^| `area_samples` ' "$top_srcdir/scenes/README.md" >"$tmpd/scenes.md"
check "probe: a scene key missing from the table is caught" \
	sh -c "! python3 '$G' --check-scene-keys '$SKINBAKE' '$tmpd/scenes.md' >/dev/null"
sed 's/^| `bumps` |/| `bumps`, `glow` |/' "$top_srcdir/scenes/README.md" >"$tmpd/scenes.md"
check "probe: a key the reader does not take is caught" \
	sh -c "! python3 '$G' --check-scene-keys '$SKINBAKE' '$tmpd/scenes.md' >/dev/null"
T="$top_builddir/tests/scene_keys_table"
check "scenes/README.md: the key tables are generated from the reader's table" \
	python3 "$G" --scene --check "$T" "$top_srcdir/scenes/README.md"
sed 's/^| `radius` | number | units | 1e-9 to 1e9 | 1 |/| `radius` | number | units | 1e-9 to 1e9 | 2 |/' \
	"$top_srcdir/scenes/README.md" >"$tmpd/scenes.md"
check "probe: a scene key's default edited by hand is caught" \
	sh -c "! python3 '$G' --scene --check '$T' '$tmpd/scenes.md' >/dev/null"
tap_done
