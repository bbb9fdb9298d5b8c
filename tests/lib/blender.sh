# Blender helpers of the shell tests (sourced after tests/tap.sh):
#   blender_require   fail the test, saying how to get it, when BLENDER is empty
#   B ARGS...         Debian's (or configure's) Blender, headless, factory settings, a Python
#                     error as exit status 1, ten minutes at most
#   val KEY FILE      the last "KEY value..." line's value in FILE (what the tests' Blender
#                     scripts print, e.g. SKINBAKE_LIGHTS)
blender_require() {
	if [ -z "$BLENDER" ]; then
		fail "blender is missing (BLENDER is empty; the project's set-up installs it)"
		tap_done
		exit 1
	fi
}
B() { timeout 600 "$BLENDER" -b --factory-startup -noaudio --python-exit-code 1 "$@"; }
val() { sed -n "s/^$1 //p" "$2" | tail -1; }
