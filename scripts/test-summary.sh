#!/bin/sh
# Print automake's test-suite summary as one plain closing line.
log=${1:-test-suite.log}
if ! test -f "$log"; then echo "0 passed, 1 failed"; exit 0; fi
awk '/^# PASS:/{p=$3} /^# FAIL:/{f=$3} /^# XPASS:/{x=$3} /^# ERROR:/{e=$3} /^# SKIP:/{s=$3}
     END{printf "%d passed, %d failed, %d skipped\n", p, f+x+e, s}' "$log"
