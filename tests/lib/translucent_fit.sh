# The Blender translucent tests' version gate (sourced after tests/tap.sh; uses the caller's
# B (Blender in the background), $imp (import_skin.py) and $tmpd):
#   translucent_fit SET BLVER WHAT
#       0 when the image set SET holds a translucent fit for Blender BLVER (major.minor).
#       Else the importer must refuse the set naming the versions it has (the export
#       calibrates 3.4, 4.5 and 5.0; Debian 13's 4.3, say, has none): two checks, then WHAT,
#       the checks that need this version's fit, skipped with a line saying so; returns 1.
translucent_fit() {
	_has=$(python3 -c 'import json,sys
print(int(any(v.get("blender") == sys.argv[2] for v in json.load(open(sys.argv[1]))["translucent"]["versions"])))' \
		"$1/manifest.json" "$2" 2>/dev/null)
	[ "$_has" = 1 ] && return 0
	B --python "$imp" -- "$1" --mode exact --scene box --samples 1 --render "$tmpd/nofit.exr" >"$tmpd/nofit.log" 2>&1
	_rc=$?
	check "Blender $2 has no translucent fit in the set: the importer refuses it (exit $_rc, no render)" \
		test $_rc -eq 2 -a ! -s "$tmpd/nofit.exr"
	check "  ... naming the versions it has: $(sed -n 's/.*translucent.versions has fits for Blender \(.*\), not for this.*/\1/p' "$tmpd/nofit.log")" \
		grep -q "translucent.versions has fits for Blender .* not for this Blender" "$tmpd/nofit.log"
	skip "Blender $2: $3 need this version's fit (make calibrate-blender with this Blender adds one)"
	return 1
}
