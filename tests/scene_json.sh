#!/bin/sh
# skinbake scene: every shipped scene file written as scene.json
# (docs/scene-json.md) parses with a strict JSON parser (no NaN, Infinity),
# and its values agree with the scene file read independently here: the
# camera, each light's direction (unit, from position toward point_at),
# the objects, and each object's to_world matrix (a mesh's includes the
# mirror of z: negative determinant; a primitive's does not).  Bad input:
# exit 2 and no file; a failed write: exit 1 and no file.
. "$top_srcdir/tests/tap.sh"
S=$SKINBAKE
for f in "$top_srcdir"/scenes/*.scene; do
	n=$(basename "$f" .scene)
	if ! "$S" scene --scene "$f" --out "$tmpd/$n.json" 2>"$tmpd/err"; then
		fail "$n: skinbake scene failed: $(cat "$tmpd/err")"
		continue
	fi
	if python3 - "$f" "$tmpd/$n.json" >"$tmpd/why" 2>&1 <<'PY'; then ok "$n: scene.json is strict JSON and agrees with the scene file"; else fail "$n: $(cat "$tmpd/why")"; fi
import configparser, json, math, sys
def refuse(c):
    raise ValueError("non-JSON constant " + c)
j = json.load(open(sys.argv[2]), parse_constant=refuse)
ini = configparser.ConfigParser(inline_comment_prefixes=(";", "#"), comment_prefixes=(";", "#"))
ini.read(sys.argv[1])
def vec(s):
    return [float(t) for t in s.replace(",", " ").replace("<", " ").replace(">", " ").split()]
def close(a, b, what):
    if any(abs(x - y) > 1e-9 * (1 + abs(y)) for x, y in zip(a, b)) or len(a) != len(b):
        raise SystemExit("%s: %s != %s" % (what, a, b))
assert j["format"] == "skinbake-scene" and j["version"] == 1
cam = ini["camera"]
close(j["camera"]["location"], vec(cam.get("location", "0 0 0")), "camera location")
assert j["camera"]["type"] == cam["type"].strip()
if cam["type"].strip() == "perspective":
    close([j["camera"]["horizontal_fov_deg"]], [float(cam["angle"])], "camera angle")
lights = [s for s in ini.sections() if s.startswith("light")]
assert len(j["lights"]) == len(lights), "light count"
for l, sec in zip(j["lights"], lights):
    k = ini[sec]
    assert l["name"] == sec[6:], (l["name"], sec)
    close(l["position"], vec(k.get("position", "0 0 0")), sec + " position")
    if l["type"] == "parallel":
        p, q = vec(k.get("position", "0 0 0")), vec(k.get("point_at", "0 0 0"))
        d = [b - a for a, b in zip(p, q)]
        n = math.sqrt(sum(x * x for x in d))
        close(l["direction"], [x / n for x in d], sec + " direction")
objs = [s for s in ini.sections() if s.startswith("object")]
assert [o["name"] for o in j["objects"]] == [s[7:] for s in objs], "object names"
for o, sec in zip(j["objects"], objs):
    m = o["to_world"]
    det = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
           + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    s3 = o["scale"] ** 3
    close([det], [-s3 if o["shape"] == "mesh" else s3], sec + " to_world determinant")
    close(m[3], [0, 0, 0, 1], sec + " to_world last row")
    close([r[3] for r in m[:3]], o["translate"], sec + " to_world translation")
PY
done
# Bad input and failed writes leave nothing.
printf '[camera]\ntype = sideways\n' >"$tmpd/bad.scene"
"$S" scene --scene "$tmpd/bad.scene" --out "$tmpd/bad.json" >"$tmpd/out" 2>"$tmpd/err"
rc=$?
if [ $rc = 2 ] && grep -q 'bad.scene:2: .*sideways' "$tmpd/err" && [ ! -e "$tmpd/bad.json" ]; then
	ok "a bad scene file: exit 2, the file and line named, no scene.json"
else
	fail "a bad scene file: exit $rc, $(cat "$tmpd/err")"
fi
"$S" scene --scene "$top_srcdir/scenes/sphere.scene" --out "$tmpd/nodir/scene.json" >"$tmpd/out" 2>"$tmpd/err"
rc=$?
if [ $rc = 1 ] && [ -s "$tmpd/err" ] && [ ! -e "$tmpd/nodir" ]; then
	ok "an unwritable --out: exit 1 and a message"
else
	fail "an unwritable --out: exit $rc"
fi
tap_done
