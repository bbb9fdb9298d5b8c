#!/bin/sh
# Every file skinbake reads is checked before use (issue 12, item 1): tampered
# presets, scene files, texture INI files, texture directories and Blender
# image sets (as exporters/blender/import_skin.py reads them) each give exit
# status 2, a message naming the file, the key and the value or what was
# expected, and no output.  The bad inputs are counted; the last line says
# how many were tried.  Costs about 15 s (one Blender start runs the image-set
# reader over all its tampered sets; one more runs import_skin.py itself).
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
B="$SKINBAKE"
T=$top_srcdir
cd "$tmpd" || exit 1
nbad=0

# bad DESC PATTERN OUT CMD...: CMD exits 2, stderr matches PATTERN (grep -E),
# and OUT does not exist afterwards (tests/lib/refused.sh)
refused_ere=1
bad() {
	b_d=$1 b_p=$2 b_o=$3
	shift 3
	nbad=$((nbad + 1))
	refused "$b_d" "$b_p" "$b_o" "$@"
}

# ---- the good inputs
"$B" bake --preset paper --solver ad --theta-nodes 3 --resolution 9x6 --radial-error 0.2 --r-bins 20 --out bk \
	--quiet || fail "good bake"
"$B" texture --size 16 --out tx --quiet || fail "good texture"
"$B" export blender --bake bk --textures tx --out bl --lut-cos 8 --lut-phi 3 > /dev/null || fail "good image set"
# refstack, not paper: the edits below match its printed values, and it is
# fixed for the tests (docs/presets.md).
"$B" preset show refstack --ini > p.ini || fail "good preset"
sed "s|^preset = paper|preset = paper|" "$T/scenes/sphere.scene" > s.scene

# ---- presets (bake --preset-file)
preset() {
	desc=$1 pat=$2 expr=$3
	sed "$expr" p.ini > t.ini
	# an edit that matches nothing would bake a good preset: say so
	if cmp -s p.ini t.ini; then
		fail "preset: $desc: the edit '$expr' changes nothing in p.ini"
		return
	fi
	bad "preset: $desc" "t\.ini:[0-9]+: .*$pat" o "$B" bake --preset-file t.ini --out o --solver ad --theta-nodes 1 \
		--resolution 3x3 --quiet
}
preset "g out of range" "epidermis.g = 1.5: out of range \[-0.99, 0.99\]" 's/^g = 0.8/g = 1.5/'
preset "negative blood" "dermis.blood = -1: out of range" 's/^blood = 0.02/blood = -1/'
preset "hexadecimal" "epidermis.n = 0x10: not a decimal number" 's/^n = 1.4$/n = 0x10/'
preset "nan" "dermis.thickness = nan: not a decimal number" 's/^thickness = 0.25/thickness = nan/'
preset "1e999" "dermis.thickness = 1e999: not a decimal number" 's/^thickness = 0.25/thickness = 1e999/'
preset "text for a number" "epidermis.musp_power = abc: not a decimal number" 's/^musp_power = 0.58/musp_power = abc/'
preset "repeated key" "epidermis.melanin is given twice" 's/^melanin = 0.025/melanin = 0.025\nmelanin = 0.03/'
preset "repeated key in a reopened section" "dermis.blood is given twice" '$s/$/\n[dermis]\nblood = 0.03/'
preset "unknown key" "unknown key 'so2x' in \[dermis\]" 's/^so2 = 0.75/so2x = 0.75/'
preset "unknown section" "unknown section \[surfce\]" 's/^\[surface\]/[surfce]/'
preset "empty unknown section" "unknown section \[extra\]" '$s/$/\n[extra]/'
preset "key on a header line" "text after the section header \[dermis\]" 's/^\[dermis\]/[dermis] thickness = 1/'
preset "wavelengths repeated" "skin.wavelengths = 470, 470, 656" 's/^wavelengths = 470, 550, 656/wavelengths = 470, 470, 656/'
preset "unknown model" "skin.model = foo: not one of" 's/^model = tables/model = foo/'
preset "roughness above 1" "surface.roughness_skin = 2: out of range" 's/^roughness_skin = 0.35/roughness_skin = 2/'
preset "transport roughness above 1" "surface.roughness = 1.5: out of range \[0, 1\]" \
	's/^roughness_skin = 0.35/roughness_skin = 0.35\nroughness = 1.5/'
preset "negative top roughness" "dermis.top_roughness = -0.1: out of range" 's/^\[dermis\]/[dermis]\ntop_roughness = -0.1/'
preset "index below 1" "sebum.n = 0.5: out of range \[1, 2\]" 's/^n = 1.5/n = 0.5/'
preset "override out of range" "override.470: epidermis.mua = -3: out of range" 's/^epidermis.mua = 84.6/epidermis.mua = -3/'
preset "override wavelength out of range" "\[override.1000\]: wavelength 1000 nm is out of range" \
	's/^\[override.470\]/[override.1000]/'
preset "override unknown key" "unknown key 'epidermis.foo' in \[override.470\]" 's/^epidermis.mua = 84.6/epidermis.foo = 3/'
preset "override repeated" "override.470: epidermis.mua is given twice" \
	's/^epidermis.mua = 84.6/epidermis.mua = 3\nepidermis.mua = 4/'
preset "empty name" "skin.name = : use letters" 's/^name = refstack/name = /'

# ---- scene files (export pov --scene)
scene() {
	desc=$1 pat=$2 expr=$3
	sed "$expr" "$T/scenes/sphere.scene" > t.scene
	if cmp -s "$T/scenes/sphere.scene" t.scene; then
		fail "scene: $desc: the edit '$expr' changes nothing in sphere.scene"
		return
	fi
	bad "scene: $desc" "t\.scene:[0-9]+: .*$pat" o "$B" export pov --bake bk --scene t.scene --out o \
		--data-dir "$T/exporters/pov"
}
scene "hexadecimal" "width = '0x80' is not a decimal number in \[16, 8192\]" 's/^width = 128/width = 0x80/'
scene "out of range" "width = -5 is out of range \[16, 8192\]" 's/^width = 128/width = -5/'
scene "1e999" "unit_mm = '1e999' is not a decimal number" 's/^unit_mm = 10/unit_mm = 1e999/'
scene "repeated key" "\[object ball\]: radius is given twice" 's/^radius = 1/radius = 1\nradius = 2/'
scene "repeated key in a reopened section" "\[light key\]: color is given twice" '$s/$/\n[light key]\ncolor = 1 1 1/'
scene "unknown key" "unknown key 'radiuss'" 's/^radius = 1/radiuss = 1/'
scene "unknown section" "unknown section \[camra\]" 's/^\[camera\]/[camra]/'
scene "key on a header line" "text after the section header \[object ball\]" 's/^\[object ball\]/[object ball] shape = sphere/'
scene "unknown light type" "type = 'laser' is not parallel or point" 's/^type = parallel/type = laser/'
scene "two numbers for a colour" "color = '0.8 0.8' is not three numbers" 's/^color = 0.8 0.8 0.8/color = 0.8 0.8/'
scene "nan in a vector" "location = '0 0 nan' is not three numbers" 's/^location = 0 0 -10/location = 0 0 nan/'
scene "camera at its target" "location and look_at coincide" 's/^location = 0 0 -10/location = 0 0 0/'
scene "unknown material" "material = 'nope' is not" 's/^material = skin/material = nope/'
scene "unknown shape" "shape = 'cube' is not one of" 's/^shape = sphere/shape = cube/'
scene "unknown site" "site = 'moon' is not a site name" 's/^site = face/site = moon/'
scene "bad section name" "'sk-in!' is not a name" 's/^\[skin skin\]/[skin sk-in!]/'
scene "negative camera width" "width = -1 is out of range" 's/^width = 2.2/width = -1/'

# ---- texture INI files (texture --preset-file)
texini() {
	desc=$1 pat=$2 text=$3
	printf "$text" > t.ini
	bad "texture INI: $desc" "t\.ini:[0-9]+: .*$pat" o "$B" texture --preset-file t.ini --size 16 --out o --quiet
}
texini "hexadecimal" "pore_depth = '0x10' is not a decimal number in \[0, 2000\] um" '[texture]\npore_depth = 0x10\n'
texini "repeated key" "pore_depth is given twice in \[texture\] \(first on line 2\)" \
	'[texture]\npore_depth = 50\npore_depth = 60\n'
texini "repeated site" "site is given twice" '[texture]\nsite = hand\nsite = face\n'
texini "unknown section" "unknown section \[textur\]" '[textur]\npore_depth = 50\n'
texini "key outside a section" "key 'pore_depth' outside the \[texture\] section" 'pore_depth = 50\n'
texini "unknown key" "unknown key 'pore_dept'" '[texture]\npore_dept = 50\n'
texini "fraction for a whole number" "size = 17.5 is not a whole number" '[texture]\nsize = 17.5\n'
texini "out of range" "pore_density = 500 is out of range" '[texture]\npore_density = 500\n'
texini "unknown site" "unknown site 'moon'" '[texture]\nsite = moon\n'

# ---- texture directories (export blender --textures; texdir_load)
# pngtool.py IN OUT [key=value | key=- | size=N | bits=8]: height.png with
# tEXt values changed or dropped, or redrawn at another size or bit depth
cat > pngtool.py <<'EOF'
import struct, sys, zlib
src, dst, edits = sys.argv[1], sys.argv[2], dict(a.split("=", 1) for a in sys.argv[3:])
b = open(src, "rb").read()
pos, chunks = 8, []
while pos < len(b):
    (n,) = struct.unpack_from(">I", b, pos)
    chunks.append((b[pos + 4:pos + 8], b[pos + 8:pos + 8 + n]))
    pos += 12 + n
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
out = []
for kind, data in chunks:
    if kind == b"tEXt":
        key = data.split(b"\0")[0].decode()
        if key in edits:
            if edits[key] == "-":
                continue
            data = key.encode() + b"\0" + edits[key].encode()
    if kind == b"IHDR" and ("size" in edits or "bits" in edits):
        w, h, depth, ctype = struct.unpack(">IIBB", data[:10])
        w = h = int(edits.get("size", w))
        depth = int(edits.get("bits", depth))
        data = struct.pack(">IIBBBBB", w, h, depth, ctype, 0, 0, 0)
        chans = {0: 1, 2: 3}[ctype]
        raw = b"".join(b"\0" + bytes(w * chans * depth // 8) for _ in range(h))
        out.append(chunk(kind, data))
        out.append(chunk(b"IDAT", zlib.compress(raw)))
        continue
    if kind == b"IDAT" and ("size" in edits or "bits" in edits):
        continue
    out.append(chunk(kind, data))
open(dst, "wb").write(b[:8] + b"".join(out))
EOF
nosums() { python3 -c "import json,sys; m=json.load(open(sys.argv[1])); m.pop('checksums', None); json.dump(m, open(sys.argv[1],'w'))" "$1"; }
texdir() {
	desc=$1 pat=$2
	shift 2
	# without the checksums (a directory made elsewhere, or before them):
	# the checks of the files themselves (tests/manifest_check.sh: checksums)
	rm -rf t && cp -r tx t && nosums t/manifest.json && "$@"
	bad "texture directory: $desc" "$pat" o "$B" export blender --bake bk --textures t --out o --lut-cos 8 --lut-phi 3
}
png() { python3 pngtool.py "tx/$1" "t/$1" "$2"; }
jset() { python3 -c "import json,sys; m=json.load(open('tx/manifest.json')); exec(sys.argv[1]); json.dump(m, open('t/manifest.json','w'))" "$1"; }
texdir "8-bit height.png" "t/height.png: 1 channel\(s\) at 8 bits; expected 16-bit gray" png height.png bits=8
texdir "height.png of 1 pixel" "t/height.png: 1x1 pixels; expected each side in \[2, 16384\]" png height.png size=1
texdir "normal.png of another size" "t/normal.png is 32x32 but t/height.png is 16x16" png normal.png size=32
texdir "tile_mm inf" "t/height.png: tEXt skinbake:tile_mm is inf; expected a length in \[0.5, 500\] mm" \
	png height.png skinbake:tile_mm=inf
texdir "tile_mm 0.1" "tEXt skinbake:tile_mm is 0.1; expected a length in \[0.5, 500\] mm" png height.png skinbake:tile_mm=0.1
texdir "tile_mm missing" "tEXt skinbake:tile_mm is missing" png height.png skinbake:tile_mm=-
texdir "height_min nan" "tEXt skinbake:height_min_um is nan; expected a finite height" png height.png skinbake:height_min_um=nan
texdir "height_max missing" "tEXt skinbake:height_max_um is missing" png height.png skinbake:height_max_um=-
texdir "height_min above height_max" "skinbake:height_min_um = 99 is above skinbake:height_max_um" \
	png height.png skinbake:height_min_um=99
texdir "manifest size_px" "t/manifest.json: key size_px is 32 but height.png is 16x16; expected 16" jset "m['size_px']=32"
texdir "manifest size_px as text" "t/manifest.json: key size_px is \"16\"" jset "m['size_px']='16'"
texdir "manifest tile_mm" "t/manifest.json: key tile_mm = 9 disagrees with height.png \(8\)" jset "m['tile_mm']=9"
texdir "manifest height_max_um" "t/manifest.json: key height_max_um = 1000 disagrees" jset "m['height_max_um']=1000"
texdir "manifest kind" "t/manifest.json: key kind is \"skinbake bake\"; expected \"skinbake texture\"" \
	jset "m['kind']='skinbake bake'"
texdir "manifest not JSON" "t/manifest.json: not a JSON object" sh -c 'echo "{oops" > t/manifest.json'

# ---- Blender image sets: import_skin.py's reader in one Blender process
if ! command -v blender > /dev/null 2>&1; then
	skip "blender is missing (scripts/setup.sh installs it)"
	echo "# $nbad bad inputs tried"
	tap_done
	exit
fi
mkdir sets
# iset NAME PATTERN PYTHON: bl copied to sets/NAME, PYTHON run on its manifest m (or files)
iset() {
	rm -rf "sets/$1" && cp -r bl "sets/$1"
	python3 -c "import json,sys; p='sets/$1/manifest.json'; m=json.load(open(p)); exec(sys.argv[1]); json.dump(m, open(p,'w'))" "$3"
	printf '%s\t%s\n' "$1" "$2" >> sets/expect.tsv
	nbad=$((nbad + 1))
}
iset ior0 '"ior" is 0.0, expected a number in \[1, 3\]' "m['ior']=0"
iset iorstr '"ior" is .1.4., expected float' "m['ior']='1.4'"
iset rough '"roughness" is -0.5, expected a number in \[0, 1\]' "m['roughness']=-0.5"
iset sssinf '"sss_radius_m" is \[inf' "m['sss_radius_m'][0]=float('inf')"
iset alb2 '"albedo_rgb" is \[.*\], expected 3 numbers' "m['albedo_rgb']=m['albedo_rgb'][:2]"
iset width0 'files.albedo: "width" is 0, expected a number in \[1, 65536\]' "m['files']['albedo']['width']=0"
iset width17 'albedo.exr: 16x16 px, manifest.json says 17x16' "m['files']['albedo']['width']=17"
iset chan 'manifest.json files.albedo.channels is not one of' "m['files']['albedo']['channels']='R,G'"
iset chanY 'brdf_lut.exr: channels B .type 2., G .type 2., R .type 2.; manifest.json files.brdf_lut.channels says Y' \
	"m['files']['brdf_lut']['channels']='Y'"
iset pngtype 'normal.png: colour type 2 at 16 bits; manifest.json files.normal.channels says gray' \
	"m['files']['normal']['channels']='gray'"
iset path 'files.albedo: "path" is .\.\./albedo.exr., expected a file name in the set' \
	"m['files']['albedo']['path']='../albedo.exr'"
iset lut 'brdf_lut 9 x 3 nodes does not match' "m['brdf_lut']['cos_nodes']=9"
iset sun 'exact.sun_direction is \[0, 0, -1\], expected 3 numbers with z > 0' "m['exact']['sun_direction']=[0,0,-1]"
iset sunw 'exact: "sun_strength_w_m2" is -1.0, expected a number in \[0, 1e\+06\]' "m['exact']['sun_strength_w_m2']=-1"
iset tile 'detail: "tile_mm" is 0.0, expected a number in \[0.5, 500\]' "m['detail']['tile_mm']=0"
iset nz 'detail: "mean_normal_z" is 2.0, expected a number in \[0.001, 1\]' "m['detail']['mean_normal_z']=2"
iset nodes 'general_fit: "cos_view_nodes" is .*expected at least 2 ascending numbers' \
	"m['general_fit']['cos_view_nodes']=m['general_fit']['cos_view_nodes'][::-1]"
iset gl 'general_fit: "glossy_rgb" is not [0-9]+ RGB triples' "m['general_fit']['glossy_rgb']=m['general_fit']['glossy_rgb'][1:]"
iset spior 'general_fit: "specular_ior" is 0.0, expected a number in \[1, 3\]' "m['general_fit']['specular_ior']=0"
iset glr 'general_fit: "glossy_roughness" is .a., expected float' "m['general_fit']['glossy_roughness']='a'"
iset ver 'format_version 2 is not supported' "m['format_version']=2"
iset png8 'height.png: colour type 0 at 8 bits; manifest.json files.height.channels says gray' \
	"m.pop('checksums'); import subprocess; subprocess.check_call(['python3', 'pngtool.py', 'bl/height.png', 'sets/png8/height.png', 'bits=8'])"
# Checksums (issue 23): a file changed after the export, a malformed entry.
iset flip 'brdf_lut.exr has changed since its manifest was written' \
	"b = bytearray(open('sets/flip/brdf_lut.exr', 'rb').read()); b[len(b) // 2] ^= 1; open('sets/flip/brdf_lut.exr', 'wb').write(b)"
iset sumbad 'checksums.albedo.exr is .md5:1., expected a file of the set' "m['checksums']['albedo.exr'] = 'md5:1'"
cat > reader.py <<EOF
import sys
sys.argv = ["import_skin.py"]
sys.path.insert(0, "$T/exporters/blender")
import import_skin
for line in open("sets/expect.tsv"):
    name = line.split("\t")[0]
    try:
        import_skin.read_manifest("sets/" + name)
        print("RESULT", name, "accepted")
    except import_skin.SkinbakeError as e:
        print("RESULT", name, str(e).replace("\n", " "))
EOF
blender -b --factory-startup --python-exit-code 1 --python reader.py > reader.out 2>&1 || fail "blender reader.py: $(tail -3 reader.out)"
while IFS="$(printf '\t')" read -r name pat; do
	msg=$(grep "^RESULT $name " reader.out | cut -d' ' -f3-)
	if printf '%s\n' "$msg" | grep -q "sets/$name/" && printf '%s\n' "$msg" | grep -Eq -- "$pat"; then
		ok "image set: $name"
	else
		fail "image set: $name: $msg"
	fi
done < sets/expect.tsv
# And once through import_skin.py's command line: exit 2, no .blend written.
bad "image set through import_skin.py: exit 2, no output" "import_skin.py: error: .*sets/ior0/manifest.json: \"ior\" is 0.0" \
	out.blend blender -b --factory-startup --python-exit-code 1 --python "$T/exporters/blender/import_skin.py" -- sets/ior0 \
	--save out.blend
nbad=$((nbad - 1))	# the same input as sets/ior0
echo "# $nbad bad inputs tried"
tap_done
