#!/bin/sh
# skinbake presets / preset show: listing, resolved layers, and bad presets
# giving a clear error, exit status 2 and no output on stdout.
. "$top_srcdir/tests/tap.sh"

out=$("$SKINBAKE" presets) && ok "presets runs" || fail "presets runs"
n=$(printf '%s\n' "$out" | wc -l)
[ "$n" -ge 14 ] && ok "presets lists $n presets" || fail "presets lists $n presets"
for p in paper paper-literal paper-dry refstack very-fair-oily very-fair-dry dark-oily dark-dry; do
	printf '%s\n' "$out" | grep -q "^$p " && ok "presets lists $p" || fail "presets lists $p"
done

# Every listed preset shows, with one row per wavelength and layer.
for p in $(printf '%s\n' "$out" | awk '{print $1}'); do
	"$SKINBAKE" preset show "$p" >"$tmpd/show" 2>"$tmpd/err" && [ ! -s "$tmpd/err" ] \
		&& ok "preset show $p" || fail "preset show $p: $(cat "$tmpd/err")"
done
"$SKINBAKE" preset show paper >"$tmpd/paper"
rows=$(grep -c '^[0-9]' "$tmpd/paper")
[ "$rows" -eq 9 ] && ok "paper: 3 wavelengths x 3 layers" || fail "paper rows = $rows"
grep -q 'mua_1/cm' "$tmpd/paper" && ok "header names units" || fail "header names units"
awk '$1 == 550 && $2 == "epidermis" && $5 == 50 && $6 == 185 { f = 1 } END { exit !f }' "$tmpd/paper" \
	&& ok "paper epidermis at 550 nm: mua 50, mus 185" || fail "paper epidermis at 550 nm"
"$SKINBAKE" preset show refstack >"$tmpd/refstack"
awk '$1 == 550 && $2 == "epidermis" && $5 == 50 && $6 == 370 { f = 1 } END { exit !f }' "$tmpd/refstack" \
	&& ok "refstack epidermis at 550 nm: mua 50, mus 370" || fail "refstack epidermis at 550 nm"
awk '$1 == 656 && $2 == "dermis" { f = 1 } END { exit !f }' "$tmpd/paper" \
	&& ok "paper has 656 nm" || fail "paper has 656 nm"

"$SKINBAKE" preset show medium-oily --wavelengths 450,550:650:100 >"$tmpd/med"
rows=$(grep -c '^[0-9]' "$tmpd/med")
[ "$rows" -eq 12 ] && ok "--wavelengths: 3 x 4 layers" || fail "--wavelengths rows = $rows"

# A preset file, and its resolved INI loading back.
cat >"$tmpd/mine.ini" <<'INI'
[skin]
base = olive-oily
[dermis]
blood = 0.04
INI
"$SKINBAKE" preset show --preset-file "$tmpd/mine.ini" --wavelengths 550 >"$tmpd/mine" \
	&& grep -q '^# preset mine:' "$tmpd/mine" && ok "--preset-file" || fail "--preset-file"
"$SKINBAKE" preset show --preset-file "$tmpd/mine.ini" --ini >"$tmpd/resolved.ini" \
	&& "$SKINBAKE" preset show --preset-file "$tmpd/resolved.ini" --wavelengths 550 >"$tmpd/mine2" \
	&& [ "$(grep '^5' "$tmpd/mine")" = "$(grep '^5' "$tmpd/mine2")" ] \
	&& ok "--ini round-trips" || fail "--ini round-trips"
"$SKINBAKE" preset cat dark-dry | grep -q '^base = dark-oily' && ok "preset cat" || fail "preset cat"
"$SKINBAKE" preset keys | grep -q '^dermis.blood' && ok "preset keys" || fail "preset keys"

# bad_case DESC EXPECTED-MESSAGE-FRAGMENT ARGS...: exit 2, message, empty stdout.
bad_case() {
	d=$1; msg=$2; shift 2
	"$SKINBAKE" "$@" >"$tmpd/o" 2>"$tmpd/e"; rc=$?
	if [ "$rc" -eq 2 ] && [ ! -s "$tmpd/o" ] && grep -qF -- "$msg" "$tmpd/e"; then
		ok "$d"
	else
		fail "$d (exit $rc, stderr: $(cat "$tmpd/e"), stdout $(wc -c <"$tmpd/o") bytes)"
	fi
}
printf '[dermis]\nblood = 0.1\nfoo = 1\n' >"$tmpd/unknown.ini"
bad_case "unknown key" "unknown.ini:3: unknown key 'foo' in [dermis]" preset show --preset-file "$tmpd/unknown.ini"
printf '[epidermis]\nmelanin = 0.7\n' >"$tmpd/range.ini"
bad_case "value out of range" "range.ini:2: epidermis.melanin = 0.7: out of range [0, 0.5]" \
	preset show --preset-file "$tmpd/range.ini"
{ printf '[skin]\ndescription = '; head -c 300 /dev/zero | tr '\0' x; printf '\n'; } >"$tmpd/long.ini"
bad_case "over-long line" "long.ini:2: line 2 is longer than 199 characters" preset show --preset-file "$tmpd/long.ini"
bad_case "missing file" "--preset-file = '$tmpd/none.ini': No such file or directory" preset show --preset-file "$tmpd/none.ini"
bad_case "unknown preset" "unknown preset 'purple' (presets: paper, paper-dry," preset show purple
bad_case "paper at an untabulated wavelength" "tabulates only 470, 550 and 656 nm" preset show paper --wavelengths 500
bad_case "wavelength out of range" "--wavelengths = 800 is out of range [380, 780] nm" preset show medium-oily --wavelengths 800
bad_case "no name" "either a preset NAME or --preset-file" preset show
bad_case "unknown action" "unknown action 'frobnicate'" preset frobnicate
tap_done
