# Sourced by the Mitsuba tests (after tap.sh): sets MTS_PY to a Python that can
# import mitsuba and drjit (MITSUBA_PYTHON, the project venv .venv, python3), with
# PYTHONPATH reaching exporters/mitsuba; MTS_PY is empty when there is none.
MTS_PY=
for py in "${MITSUBA_PYTHON:-}" "$top_srcdir/.venv/bin/python" "${top_builddir:-.}/.venv/bin/python" python3; do
	[ -n "$py" ] || continue
	if "$py" -c 'import mitsuba, drjit' >/dev/null 2>&1; then
		MTS_PY=$py
		break
	fi
done
PYTHONPATH="$top_srcdir/exporters/mitsuba${PYTHONPATH:+:$PYTHONPATH}"
export PYTHONPATH
# Each test prints this and nothing else when Mitsuba is missing.
mts_skip_all() {
	echo "1..0 # SKIP mitsuba is not importable (make the project venv: scripts/setup.sh, or set MITSUBA_PYTHON)"
	exit 0
}
