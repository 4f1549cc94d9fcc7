#!/usr/bin/env bash
# The resume's time precision (scripts/ResumeFunctions, _setTimePrecision): a run stopped at a
# time name of 12 digits (1.13999722736) resumes with controlDict timePrecision 12, or OpenFOAM
# restarts at 16 digits and looks for a directory that does not exist; a name the controlDict's
# precision already holds changes nothing. Usage: test_resume_precision.sh ROOT WORKDIR
set -u
root=$1 work=$2
rm -rf "$work" && mkdir -p "$work/system" && cd "$work" || exit 1
. "$root/scripts/ResumeFunctions"
fail=0
expect() {  # expect WHAT PATTERN: system/controlDict holds PATTERN
  if grep -qE "$2" system/controlDict; then echo "  ok   $1"; else echo "  FAIL $1"; fail=1; fi
}
printf 'application mixflowCoupled;\ntimePrecision   8;\n' >system/controlDict
_setTimePrecision 0.30000005
expect "an 8-digit name keeps timePrecision 8" '^timePrecision +8;'
_setTimePrecision 1.13999722736
expect "a 12-digit name raises timePrecision to 12" '^timePrecision +12;'
_setTimePrecision 2.369998939388497
expect "a 16-digit name raises it to 16" '^timePrecision +16;'
printf 'application mixflowCoupled;\n' >system/controlDict
_setTimePrecision 1.13999722736
expect "without the entry (OpenFOAM's 6), 12 is appended" '^timePrecision 12;'
# A prepared case: the precision in the controlDict.generated that system/controlDict includes.
printf '#include "controlDict.generated"\n' >system/controlDict
printf 'timePrecision   8;\n' >system/controlDict.generated
_setTimePrecision 0.30000005
expect "the included 8 holds an 8-digit name: nothing appended" '^#include'
if grep -q timePrecision system/controlDict; then echo "  FAIL appended to an included 8"; fail=1; fi
_setTimePrecision 1.13999722736
expect "a 12-digit name appends 12 after the include" '^timePrecision 12;'
[ "$fail" -eq 0 ] && echo PASS || echo FAIL
exit "$fail"
