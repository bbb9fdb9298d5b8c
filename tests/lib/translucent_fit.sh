# The Blender translucent tests' version gate (sourced after tests/tap.sh; uses the caller's
# B (Blender in the background), $imp (import_skin.py) and $tmpd):
#   translucent_fit SET BLVER WHAT
#       0 when the image set SET holds a translucent fit for Blender BLVER (major.minor).
#       Else (the export calibrates 3.4, 4.5 and 5.0; Debian 13's 4.3, say, has none): a
#       family set must be refused by the importer naming the versions it has (two checks);
#       a single bake's set imports with the fallback, the node's far field as a diffuse and
#       a message saying so (two checks; blender_translucent.sh checks its flat box).  Then
#       WHAT, the checks that need this version's fit, skipped with a line saying so; returns 1.
translucent_fit() {
	_has=$(python3 -c 'import json,sys
m = json.load(open(sys.argv[1]))
print(int(any(v.get("blender") == sys.argv[2] for v in m["translucent"]["versions"])), int("family" in m))' \
		"$1/manifest.json" "$2" 2>/dev/null)
	[ "${_has% *}" = 1 ] && return 0
	B --python "$imp" -- "$1" --mode exact --scene box --samples 1 --render "$tmpd/nofit.exr" >"$tmpd/nofit.log" 2>&1
	_rc=$?
	if [ "${_has#* }" = 1 ]; then
		check "Blender $2 has no translucent fit in the family set: the importer refuses it (exit $_rc, no render)" \
			test $_rc -eq 2 -a ! -s "$tmpd/nofit.exr"
		check "  ... naming the versions it has: $(sed -n 's/.*translucent.versions has fits for Blender \(.*\), not for this.*/\1/p' "$tmpd/nofit.log")" \
			grep -q "translucent.versions has fits for Blender .* not for this Blender" "$tmpd/nofit.log"
	else
		check "Blender $2 has no translucent fit in the set: the importer renders it with the fallback (exit $_rc)" \
			test $_rc -eq 0 -a -s "$tmpd/nofit.exr"
		check "  ... saying so: $(sed -n 's/.*translucent: no fit for this Blender \([^ ]*\) in the set (fits for \([^)]*\)).*/\1, fits for \2/p' "$tmpd/nofit.log")" \
			grep -q "translucent: no fit for this Blender .* its far field as a diffuse" "$tmpd/nofit.log"
	fi
	skip "Blender $2: $3 need this version's fit (make calibrate-blender with this Blender adds one)"
	return 1
}
