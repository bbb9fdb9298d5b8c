#!/bin/sh
# The command-line rules of every command described by an option table
# (src/cli/opt.h): a repeated option, a hexadecimal, inf, nan or junk
# number, a value out of range, a missing input path, a bad output directory
# ('' , an existing file, a missing parent) each end with exit status 2, one
# message "skinbake CMD: ..." naming the option, the value and the range,
# nothing on stdout and no output left behind; --help goes to stdout with
# status 0 and lists every option of the command's table with its default,
# unit and range.  Costs about 3 s (two tiny bakes, one 16 px texture).
. "$top_srcdir/tests/tap.sh"
S=$SKINBAKE
nbad=0

# Fixtures: a tiny bake, a tiny texture directory, a regular file.
"$S" bake --preset paper --wavelengths 550 --theta-nodes 2 --resolution 3x3 --target-error 0 \
	--max-photons 2000 --batch-photons 100 --out "$tmpd/bake" --quiet || fail "fixture bake"
"$S" texture --size 16 --out "$tmpd/tex" --quiet || fail "fixture texture"
printf 'x\n' >"$tmpd/file"
mkdir "$tmpd/emptydir"
# A tiny family (2 members), maps and an albedo for the maps commands.
"$S" bake --preset paper --wavelengths 550 --theta-nodes 1 --resolution 1x1 --target-error 0 --max-photons 2000 \
	--batch-photons 100 --r-bins 2 --vary dermis.blood=0.01,0.02 --out "$tmpd/fam" --quiet || fail "fixture family"
"$S" maps new --family "$tmpd/fam" --size 4x4 --out "$tmpd/maps" --quiet || fail "fixture maps"
"$S" maps render-albedo --family "$tmpd/fam" --maps "$tmpd/maps" --out "$tmpd/alb.png" --quiet || fail "fixture albedo"

# bad DESC NEEDLE ARGS...: skinbake ARGS refused (tests/lib/refused.sh): exit 2, nothing on
# stdout, one line on stderr that starts "skinbake CMD" and holds the fixed string NEEDLE, no
# $tmpd/new*, $tmpd/file unchanged.  Fixed strings keep each of the some 250 calls to one process.
. "$top_srcdir/tests/lib/refused.sh"
refused_fixed=1 refused_quiet=1 refused_one_line=1 refused_kept=$tmpd/file
bad() {
	b_d=$1 b_n=$2
	shift 2
	nbad=$((nbad + 1))
	refused_prefix="skinbake $1[ :]"
	refused "$b_d" "$b_n" "$tmpd/new*" "$S" "$@"
}

# rules CMD... -- NUM VALID RANGE BADRANGE FLAG -- BASE...: the number and
# option rules for one command.  NUM is a numeric option, VALID a good value
# of it, BADRANGE a value outside RANGE (the text the message must show),
# FLAG a flag of the command ('-' if none).
rules() {
	cmd=
	while [ "$1" != -- ]; do cmd="$cmd${cmd:+ }$1"; shift; done
	shift
	num=$1 valid=$2 range=$3 badr=$4 flag=$5
	shift 6
	# shellcheck disable=SC2086
	set -- $cmd "$@"
	bad "$cmd: $num given twice" "$num is given twice ('$valid' and '$valid')" "$@" "$num" "$valid" "$num" "$valid"
	[ "$flag" = - ] || bad "$cmd: $flag given twice" "$flag is given twice" "$@" "$flag" "$flag"
	bad "$cmd: $num hexadecimal" "$num = '0x10' is not a" "$@" "$num" 0x10
	bad "$cmd: $num inf" "$num = 'inf' is not a" "$@" "$num" inf
	bad "$cmd: $num nan" "$num = 'nan' is not a" "$@" "$num" nan
	bad "$cmd: $num trailing junk" "$num = '${valid}x' is not a" "$@" "$num" "${valid}x"
	bad "$cmd: $num leading blank" "$num = ' $valid' is not a" "$@" "$num" " $valid"
	bad "$cmd: $num empty" "$num = ''" "$@" "$num" ""
	bad "$cmd: $num out of range" "$num = $badr is out of range $range" "$@" "$num" "$badr"
	bad "$cmd: $num=out of range" "$num = $badr is out of range $range" "$@" "$num=$badr"
	bad "$cmd: $num without a value" "$num needs a value" "$@" "$num"
	bad "$cmd: unknown option" "unknown option '--frobnicate'" "$@" --frobnicate 1
	bad "$cmd: abbreviated option" "unknown option '${num%?}'" "$@" "${num%?}" "$valid"
	bad "$cmd: stray argument" "unexpected argument 'stray'" "$@" stray stray2
	if "$S" $cmd --help >"$tmpd/h" 2>"$tmpd/he" && [ ! -s "$tmpd/he" ] && head -n 1 "$tmpd/h" | grep -q "^usage: skinbake $cmd " &&
	    "$S" $cmd -h | cmp -s - "$tmpd/h" && "$S" "$@" "$num" 0x10 --help | cmp -s - "$tmpd/h"; then
		ok "$cmd --help, -h, and --help after a bad value: usage on stdout, exit 0"
	else
		fail "$cmd --help"
	fi
}

# out_rules CMD... -- BASE...: the output directory rules (BASE lacks --out).
out_rules() {
	cmd=
	while [ "$1" != -- ]; do cmd="$cmd${cmd:+ }$1"; shift; done
	shift
	# shellcheck disable=SC2086
	set -- $cmd "$@"
	bad "$cmd: --out ''" "--out: empty path" "$@" --out ""
	bad "$cmd: --out FILE" "--out = '$tmpd/file' exists and is not a directory" "$@" --out "$tmpd/file"
	bad "$cmd: --out under a file" "--out = '$tmpd/file/new': Not a directory" "$@" --out "$tmpd/file/new"
	bad "$cmd: --out with a missing parent" "its parent directory '$tmpd/newp' does not exist" "$@" --out "$tmpd/newp/new"
	bad "$cmd: --out given twice" "--out is given twice" "$@" --out "$tmpd/new" --out "$tmpd/new2"
	if [ "$(id -u)" != 0 ]; then
		mkdir -p "$tmpd/ro" && chmod 555 "$tmpd/ro"
		bad "$cmd: --out in a read-only directory" "its parent directory '$tmpd/ro' is not writable" "$@" --out "$tmpd/ro/new"
	else
		skip "$cmd: --out in a read-only directory (root writes anywhere)"
	fi
}

# in_rules CMD... -- OPT KIND BASE...: an input path option; KIND dir or file.
in_rules() {
	cmd=
	while [ "$1" != -- ]; do cmd="$cmd${cmd:+ }$1"; shift; done
	shift
	opt=$1 kind=$2
	shift 2
	# shellcheck disable=SC2086
	set -- $cmd "$@"
	bad "$cmd: $opt missing" "$opt = '$tmpd/missing': No such file or directory" "$@" "$opt" "$tmpd/missing"
	bad "$cmd: $opt ''" "$opt: empty path" "$@" "$opt" ""
	if [ "$kind" = dir ]; then
		bad "$cmd: $opt a file" "$opt = '$tmpd/file': not a directory" "$@" "$opt" "$tmpd/file"
	else
		bad "$cmd: $opt a directory" "$opt = '$tmpd/emptydir': a directory, not a file" "$@" "$opt" "$tmpd/emptydir"
	fi
	bad "$cmd: $opt given twice" "$opt is given twice" "$@" "$opt" "$tmpd/x" "$opt" "$tmpd/y"
}

L="--layer d=0.1,mua=1,mus=10 --photons 100"
rules simulate -- --theta-in 30 "[0, 90) deg" 90 --json -- $L
rules simulate -- --photons 100 "[1, 1e12]" 0 --json -- --layer d=0.1,mua=1,mus=10
rules bake -- --r-bins 10 "[1, 100000]" 0 --quiet -- --preset paper --out "$tmpd/new"
rules bake -- --target-error 0.5 "[0, 1]" 2 --quiet -- --preset paper --out "$tmpd/new"
rules eval -- --phi 10 "[0, 360] deg" 400 --json -- --bake "$tmpd/bake" --theta-in 10 --theta-out 10
rules verify -- --cells 4 "[1, 100000]" 0 --json -- --bake "$tmpd/bake" --photons 1000
rules bake -- --ad-tol 0.01 "[1e-6, 0.1]" 0.5 --quiet -- --preset paper --out "$tmpd/new"
rules simulate -- --ad-tol 0.01 "[1e-6, 0.1]" 0.5 --json -- --layer d=0.1,mua=1,mus=10 --solver ad
rules texture -- --tile-mm 4 "[0.5, 500] mm" 0.1 --quiet -- --size 16 --out "$tmpd/new"
rules texture -- --size 32 "[16, 16384] px" 8 --quiet -- --out "$tmpd/new"
rules export blender -- --sun-elevation 30 "(0, 90] deg" 0 - -- --bake "$tmpd/bake" --out "$tmpd/new"
rules export blender -- --lut-cos 16 "[8, 1024]" 4 - -- --bake "$tmpd/bake" --out "$tmpd/new"
rules preset show -- --wavelengths 550 "[380, 780] nm" 300 - -- paper
rules maps fit -- --max-de 2 "(0, 100]" 0 --quiet -- --family "$tmpd/fam" --albedo "$tmpd/alb.png" --out "$tmpd/new"
rules maps render-albedo -- --bits 16 "[8, 16]" 4 --quiet -- --family "$tmpd/fam" --maps "$tmpd/maps" --out "$tmpd/new.png"

out_rules bake -- --preset paper
out_rules texture -- --size 16
out_rules export blender -- --bake "$tmpd/bake"
out_rules maps fit -- --family "$tmpd/fam" --albedo "$tmpd/alb.png"
out_rules maps new -- --family "$tmpd/fam" --size 4x4
out_rules maps edit -- --maps "$tmpd/maps" --scale dermis.blood=1.1

in_rules bake -- --preset-file file --out "$tmpd/new"
in_rules eval -- --bake dir --theta-in 1 --theta-out 1 --phi 1
in_rules verify -- --bake dir
in_rules scene -- --scene file
in_rules texture -- --preset-file file --out "$tmpd/new"
in_rules export blender -- --bake dir --out "$tmpd/new"
in_rules export blender -- --textures dir --bake "$tmpd/bake" --out "$tmpd/new"
in_rules preset show -- --preset-file file
in_rules maps fit -- --family dir --albedo "$tmpd/alb.png" --out "$tmpd/new"
in_rules maps fit -- --albedo file --family "$tmpd/fam" --out "$tmpd/new"
in_rules maps edit -- --maps dir --scale dermis.blood=1.1 --out "$tmpd/new"
in_rules maps render-albedo -- --maps dir --family "$tmpd/fam" --out "$tmpd/new.png"

# Numbers inside compound values follow the same rules.
bad "simulate --layer mua=0x10" "--layer 1: mua = '0x10' is not a decimal number in [0, 1e8] 1/cm" simulate --layer d=1,mua=0x10,mus=1
bad "simulate --layer d=nan" "--layer 1: d = 'nan' is not a decimal number in (0, inf) cm" simulate --layer d=nan,mua=1,mus=1
bad "simulate --layer g=inf" "--layer 1: g = 'inf' is not a decimal number in (-1, 1)" simulate --layer d=1,mua=1,mus=1,g=inf
bad "simulate --layer n=1.4x" "--layer 1: n = '1.4x' is not a decimal number in [1, 10]" simulate --layer d=1,mua=1,mus=1,n=1.4x
bad "simulate --layer key twice" "--layer 1: key mua is given twice" simulate --layer d=1,mua=1,mus=1,mua=2
bad "simulate --layer empty key" "--layer 2: '' is not KEY=VALUE" simulate --layer d=1,mua=1,mus=1 --layer d=1,mua=1,mus=1,
bad "bake --wavelengths hex" "--wavelengths = '0x226' is not a whole decimal number in [380, 780] nm" bake --preset paper --wavelengths 0x226 --out "$tmpd/new"
bad "bake --wavelengths twice in the list" "--wavelengths: 550 is listed twice" bake --preset paper --wavelengths 550,470,550 --out "$tmpd/new"
bad "bake --theta-in hex element" "--theta-in = '0x10' is not a decimal number in [0, 90) deg" bake --preset paper --theta-in 30,0x10 --out "$tmpd/new"
bad "bake --theta-in inf element" "--theta-in = 'inf' is not a decimal number" bake --preset paper --theta-in inf --out "$tmpd/new"
bad "bake --theta-in trailing comma" "--theta-in = '30,' has an empty element" bake --preset paper --theta-in 30, --out "$tmpd/new"
bad "bake --theta-in and --theta-nodes" "--theta-in and --theta-nodes exclude each other" bake --preset paper --theta-in 34 --theta-nodes 3 --out "$tmpd/new"
bad "bake --theta-nodes 34.5" "--theta-nodes = 34.5 is not a whole number in [1, 90]" bake --preset paper --theta-nodes 34.5 --out "$tmpd/new"
bad "bake --theta-nodes 0" "--theta-nodes = 0 is out of range [1, 90]" bake --preset paper --theta-nodes 0 --out "$tmpd/new"
bad "bake --resolution hex" "--resolution: P = '0x10' is not a whole decimal number in [1, 360]" bake --preset paper --resolution 9x0x10 --out "$tmpd/new"
bad "bake --resolution 1e400" "--resolution: T = 1e400 is out of range [1, 360]" bake --preset paper --resolution 1e400x4 --out "$tmpd/new"
bad "bake --spectral hex" "--spectral = '0x1f4' is not a whole decimal number in [380, 780] nm" bake --preset paper --spectral 400:0x1f4:10 --out "$tmpd/new"
bad "bake --spectral and --wavelengths" "--wavelengths and --spectral exclude each other" bake --preset paper --spectral 400:500:10 --wavelengths 550 --out "$tmpd/new"
bad "bake --preset and --preset-file" "--preset and --preset-file exclude each other" bake --preset paper --preset-file "$tmpd/file" --out "$tmpd/new"
bad "bake without a preset" "give one of --preset, --preset-file" bake --out "$tmpd/new"
bad "bake without --out" "--out is required" bake --preset paper
bad "bake --seed beyond 2^64-1" "--seed = 18446744073709551616 is out of range [0, 2^64-1]" bake --preset paper --seed 18446744073709551616 --out "$tmpd/new"
bad "bake --fresnel unknown" "--fresnel = 'fast' is not one of exact, schlick" bake --preset paper --fresnel fast --out "$tmpd/new"
bad "bake --solver unknown" "--solver = 'dom' is not one of auto, ad, mc" bake --preset paper --solver dom --out "$tmpd/new"
bad "simulate --solver ad with an mc option" "--photons applies to --solver mc only" simulate --layer d=1,mua=1,mus=1 --solver ad --photons 100
bad "texture --size 0x40" "--size = '0x40' is not a whole decimal number in [16, 16384] px" texture --size 0x40 --out "$tmpd/new"
bad "texture --seed hex" "--seed = '0x7' is not a whole decimal number" texture --seed 0x7 --out "$tmpd/new"
bad "texture --orientation inf" "--orientation = 'inf' is not a decimal number in [-180, 180] deg" texture --orientation inf --out "$tmpd/new"
bad "eval without --phi" "--phi is required" eval --bake "$tmpd/bake" --theta-in 1 --theta-out 1
bad "preset show --wavelengths hex step" "--wavelengths: STEP = '0x10' is not a decimal number in (0, inf) nm" preset show paper --wavelengths 470:656:0x10
bad "preset show --ini and --wavelengths" "--wavelengths and --ini exclude each other" preset show paper --ini --wavelengths 550
bad "preset cat without a name" "missing argument" preset cat
bad "preset cat, two names" "unexpected argument 'b'" preset cat paper b
bad "preset keys with an argument" "unexpected argument 'x'" preset keys x
bad "presets with an argument" "unexpected argument 'x'" presets x
bad "preset, unknown action" "unknown action 'frob' (show, cat, keys)" preset frob
bad "export, unknown exporter" "unknown action 'pbrt' (pov, blender, mitsuba)" export pbrt
bad "maps, unknown action" "unknown action 'paint' (new, fit, edit, render-albedo)" maps paint
bad "maps edit --scale hex" "--scale dermis.blood = '0x2' is not a decimal number in [0, 100]" maps edit --maps "$tmpd/maps" --scale dermis.blood=0x2 --out "$tmpd/new"
bad "maps edit --add without =" "--add = 'dermis.blood' is not KEY=VALUE" maps edit --maps "$tmpd/maps" --add dermis.blood --out "$tmpd/new"
bad "maps new --size 0x4" "--size: W = 0 is out of range [1, 16384]" maps new --family "$tmpd/fam" --size 0x4 --out "$tmpd/new"
bad "maps new --size and --like" "--size and --like exclude each other" maps new --family "$tmpd/fam" --size 4x4 --like "$tmpd/alb.png" --out "$tmpd/new"
bad "maps fit --input unknown" "--input = 'gamma' is not one of auto, srgb, linear" maps fit --family "$tmpd/fam" --albedo "$tmpd/alb.png" --input gamma --out "$tmpd/new"
bad "maps render-albedo --bits 12" "--bits = 12 is not 8 or 16" maps render-albedo --family "$tmpd/fam" --maps "$tmpd/maps" --bits 12 --out "$tmpd/new.png"
bad "bake --vary nan" "--vary dermis.blood = 'nan' is not a decimal number" bake --preset paper --vary dermis.blood=nan:0.1:3 --out "$tmpd/new"

# --out FILE is found before the work: exit 2 at once, not after the bake.
bad "bake --out FILE before a long bake" "exists and is not a directory" bake --preset paper --target-error 0 --max-photons 1e13 --out "$tmpd/file"

# Under MPI every rank sees the same bad input; one of them says so.
if [ -x "$top_builddir/skinbake-mpi" ] && command -v mpirun >/dev/null 2>&1; then
	mpirun --allow-run-as-root -np 2 "$top_builddir/skinbake-mpi" bake --preset paper --r-bins 0x10 \
		--out "$tmpd/new" >"$tmpd/o" 2>"$tmpd/e"
	rc=$? n=$(grep -c '^skinbake bake: --r-bins' "$tmpd/e")
	nbad=$((nbad + 1))
	check "mpirun -np 2: bad input exits 2, one message from 2 ranks (exit $rc, $n messages)" [ $rc = 2 -a "$n" = 1 ]
else
	skip "no skinbake-mpi or mpirun"
fi

# --theta-in is a list of angles whatever the number's form; --theta-nodes a count.
for arg in "--theta-in 34" "--theta-in 34.0" "--theta-nodes 3"; do
	rm -rf "$tmpd/th"
	# shellcheck disable=SC2086
	"$S" bake --preset paper --wavelengths 550 $arg --resolution 3x3 --target-error 0 --max-photons 3000 \
		--batch-photons 100 --out "$tmpd/th" --quiet
	python3 -c "import json; print([round(t, 9) for t in json.load(open('$tmpd/th/manifest.json'))['theta_i_deg']])" >"$tmpd/th.txt" 2>&1
	case $arg in
	*nodes*) want="[0.0, 30.0, 60.0]" ;;
	*) want="[34.0]" ;;
	esac
	check "bake $arg: theta_i_deg $(cat "$tmpd/th.txt") = $want" [ "$(cat "$tmpd/th.txt")" = "$want" ]
done

# The documented defaults are the real ones: giving each explicitly changes
# no table (the manifest differs only in the command line it records).
small="--preset paper --wavelengths 550 --theta-in 30 --resolution 3x3 --target-error 0 --max-photons 3000 --batch-photons 100 --quiet"
"$S" bake $small --out "$tmpd/d0"
# "--name value" for every option of bake --help with a one-word default,
# except those $small sets.
defs=$("$S" bake --help | python3 -c '
import re, sys
small = sys.argv[1].split()
text = re.sub(r"\n {20,}", " ", sys.stdin.read())
for m in re.finditer(r"^  (--[a-z-]+) .*[(;] *default ([^ ;)]+)\)$", text, re.M):
    if m.group(1) not in small and m.group(1) != "--theta-nodes":
        print(m.group(1), m.group(2))' "$small")
# shellcheck disable=SC2086
"$S" bake $small $defs --out "$tmpd/d1"
check "bake: the documented defaults ($(echo $defs)) change no table" sh -c \
	"cmp '$tmpd/d0/brdf.exr' '$tmpd/d1/brdf.exr' && cmp '$tmpd/d0/albedo.exr' '$tmpd/d1/albedo.exr'"
check "bake: $(echo "$defs" | wc -w) default words found" [ "$(echo "$defs" | wc -w)" -ge 10 ]

# ---- --help against the option tables -------------------------------------
# Each table entry in src/cli/cmd_*.c (export pov is not yet a table) must be
# in its command's --help with its placeholder, range, unit, default and
# requirement; texture's parameters (from geom/sites.c) with theirs.
for c in simulate bake eval verify "export blender" "preset show" texture presets "preset cat" "preset keys"; do
	f=$(echo "$c" | tr ' ' _)
	"$S" $c --help >"$tmpd/help_$f.txt"
done
python3 - "$top_srcdir/src/cli" "$tmpd" <<'EOF' >"$tmpd/table.tap"
import re, sys
src, tmp = sys.argv[1], sys.argv[2]
# A command's tables may be split over files by concept (bake: cmd_bake.c and bake_opts.c).
files = {"cmd_simulate.c": "simulate", "cmd_bake.c bake_opts.c": "bake", "cmd_eval.c": "eval",
         "cmd_export_blender.c": "export_blender", "cmd_preset.c": "preset_show", "cmd_texture.c": "texture",
         "cmd_verify.c": "verify"}
n = 0
def say(good, what):
    global n
    n += 1
    print(("ok" if good else "not ok") + " - " + what)
for fn, cmd in files.items():
    text = "".join(open(src + "/" + f).read() for f in fn.split())
    tables = re.findall(r"struct opt [a-z]+\[(?:OPT_MAX)?\] = \{(.*?)(?:OPT_END|\n\t\};)", text, re.S)
    say(tables != [], "%s: option table found" % fn)
    if not tables:
        continue
    body = "".join(tables)
    # One entry per '{ "name", OPT_' at the start of a line.
    starts = [e.start() for e in re.finditer(r'\n\t+\{ "[a-z-]+", OPT_', body)]
    entries = [body[a:b] for a, b in zip(starts, starts[1:] + [len(body)])]
    help_ = open("%s/help_%s.txt" % (tmp, cmd)).read()
    # Paragraph of each option: its line and the continuation lines.
    paras, cur = {}, None
    for line in help_.splitlines():
        mm = re.match(r"  --([a-z-]+)", line)
        if mm:
            cur = mm.group(1)
            paras[cur] = line
        elif cur and line.startswith("    "):
            paras[cur] += " " + line.strip()
        else:
            cur = None
    say(len(entries) >= 3 or cmd == "preset_show", "%s: %d table entries" % (fn, len(entries)))
    for e in entries:
        name, typ = re.search(r'\{ "([a-z-]+)", OPT_([A-Z_]+)', e).groups()
        p = re.sub(r"\s+", " ", paras.get(name, ""))
        say(p != "", "%s --%s is in --help" % (cmd, name))
        if not p:
            continue
        pos = re.findall(r'"((?:[^"\\]|\\.)*)"', e.split(".", 1)[0] if ", ." in e else e)
        meta = re.search(r'OPT_[A-Z_]+, [^,]+, "([^"]*)"', e)
        if meta:
            say(p.startswith(" --%s %s " % (name, meta.group(1))), "%s --%s shows its placeholder %s" % (cmd, name, meta.group(1)))
        d = re.search(r'OPT_[A-Z_]+, [^,]+, "[^"]*", "([^"]*)"', e) or re.search(r'\.def = "([^"]*)"', e)
        note = re.search(r'\.def_note = "([^"]*)"', e)
        if d or note:
            want = "default " + (d or note).group(1)
            say(want in p, "%s --%s shows '%s'" % (cmd, name, want))
        if typ in ("DOUBLE", "LONG", "INT", "LIST"):
            say(re.search(r" in [\[(][-0-9.e]+, ([-0-9.e]+|inf|2\^63-1)[\])]", p) is not None,
                "%s --%s shows its range" % (cmd, name))
        u = re.search(r'\.unit = "([^"]*)"', e)
        if u and typ in ("DOUBLE", "LONG", "INT", "LIST"):
            say(re.search(r"[\])] " + re.escape(u.group(1)) + r"\b", p) is not None, "%s --%s shows its unit %s after the range" % (cmd, name, u.group(1)))
        if typ == "ENUM":
            ch = re.search(r'\.choices = "([^"]*)"', e).group(1)
            say(p.startswith(" --%s %s" % (name, ch)), "%s --%s shows its choices %s" % (cmd, name, ch))
        if "OPT_REQUIRED" in e:
            say("required" in p, "%s --%s says it is required" % (cmd, name))
        x = re.search(r'\.excl = "([^"]*)"', e)
        if x:
            say(all("--" + o in p for o in x.group(1).split("|")), "%s --%s names what it excludes" % (cmd, name))
# texture: every parameter of geom/sites.c with its unit, range and site-face default.
sites = open(src + "/../geom/sites.c").read()
help_ = re.sub(r"\n {20,}", " ", open("%s/help_texture.txt" % tmp).read())
for key, unit, lo, hi in re.findall(r'\{ "([a-z-]+)", "([^"]*)", [^,]+, ([^,]+), ([^,]+), SITES_', sites):
    line = next((l for l in help_.splitlines() if l.startswith("  --%s " % key)), "")
    u = "" if unit == "1" else " " + unit
    say(re.search(r" in \[[^]]*\]" + re.escape(u) + r" \(default [^)]+\)$", line) is not None,
        "texture --%s shows range, unit%s and default: %s" % (key, u, line.strip()))
print("1..%d" % n, file=sys.stderr)
EOF
while read -r line; do
	case $line in
	"ok - "*) ok "${line#ok - }" ;;
	*) fail "${line#not ok - }" ;;
	esac
done <"$tmpd/table.tap"

# A few by hand: the exact lines a user reads.
hand() {
	f=$1 want=$2
	tr '\n' '~' <"$tmpd/help_$f.txt" | sed 's/~  *\([^- ]\)/ \1/g' | tr '~' '\n' | grep -qxF -- "$want" &&
		ok "help_$f has: $want" || fail "help_$f lacks: $want"
}
hand simulate "  --photons N            mc: photons in [1, 1e12] (default 1e6)"
hand simulate "  --theta-in DEG         incidence angle in [0, 90) deg (default 0)"
hand simulate "  --roulette-chance P    mc: roulette survival probability in (0, 1] (default 0.3)"
hand bake "  --theta-nodes N        incidence angles 90*k/N deg (k = 0 .. N-1), N in [1, 90] (not with --theta-in; default the exit nodes below 90 deg: T-1 angles 45 (1 - cos(180 k/(T-1))) deg for --resolution TxP (T >= 3; else N = 10))"
hand bake "  --theta-in LIST        incidence angles, comma-separated, each in [0, 90) deg, at most 90 (not with --theta-nodes)"
hand bake "  --r-step CM            radial bin of Rd(r) in [1e-6, 10] cm (default 0.002)"
hand bake "  --seed N               mc: random seed (exact) in [0, 2^64-1] (default 1)"
hand bake "  --solver auto|ad|mc    adding-doubling (ad), Monte Carlo (mc), or ad with mc, said on stderr, for the wavelengths where ad cannot meet --ad-tol (auto) (default auto)"
hand verify "  --cells N              table cells to recompute, each by a Monte Carlo re-run of its own (independent cells) in [1, 100000] (default 32)"
hand eval "  --phi DEG              azimuth difference: 0 back toward the light, 180 the mirror side in [0, 360] deg (required)"
hand export_blender "  --sun-strength E       sun irradiance for the importer's demo scene, in (0, 1e6] W/m^2 (default 3)"
hand export_blender "  --lut-cos N            cosine nodes per axis of brdf_lut.exr, in [8, 1024] (default 64)"
hand texture "  --size N               edge length of the square maps in [16, 16384] px (default 1024)"
hand texture "  --seed N               random seed (exact) in [0, 2^64-1] (default 1)"

echo "# $nbad bad command lines tried in this file"
tap_done
