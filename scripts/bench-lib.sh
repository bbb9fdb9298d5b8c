# Shared by the benchmark scripts (sourced; needs $W, a scratch directory).
# cpu CMD...: the smallest user + system CPU seconds of REPS runs (default 3)
# of CMD, its output discarded.  CPU time, not wall time: the machine is shared.
cpu() {
	best=
	i=0
	while [ $i -lt "${REPS:-3}" ]; do
		/usr/bin/time -f "%U %S" -o "$W/t" "$@" >/dev/null 2>&1
		c=$(awk '{ printf "%.3f", $1 + $2 }' "$W/t")
		best=$(awk -v a="$c" -v b="${best:-1e99}" 'BEGIN { print (a < b ? a : b) }')
		i=$((i + 1))
	done
	echo "$best"
}
