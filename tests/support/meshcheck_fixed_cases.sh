#!/usr/bin/env bash
# ctest meshcheck_fixed_cases: meshcheck's own hand-made cases (../shared/tools/meshcheck/tests,
# each with the verdict it must give, the failing ones included) run on the copy with the fixes
# of meshcheck_fixed.py. The fixes accept what rounding alone does; this shows they do not turn a
# verdict meshcheck's author asserted. Skipped (77) without ../shared.
# usage: meshcheck_fixed_cases.sh SOURCE_DIR
set -u
src=$1
. "$src/tests/corpus/corpus_lib.sh"
find_meshcheck "$src"
[ -n "$MCF" ] || exit 77
fixed=${MESHCHECK_FIXED_SRC:-/tmp/meshcheck-fixed-gsse-src}
[ -f "$fixed/tests/run.sh" ] || { echo "FAIL: no meshcheck cases in $fixed/tests"; exit 1; }
MESHCHECK_BUILD=${MESHCHECK_FIXED_BUILD:-/tmp/meshcheck-fixed-gsse} sh "$fixed/tests/run.sh"
