#!/usr/bin/env bash
# ctest fixture (meshcheck_build): builds ../shared's meshcheck, as shipped and with the fixes of
# meshcheck_fixed.py, once, before the tests that run it. They used to build it themselves, and
# two of them building the same folder at once on a fresh machine broke one of them.
# usage: build_meshcheck.sh SOURCE_DIR
set -u
src=$1
. "$src/tests/corpus/corpus_lib.sh"
find_meshcheck "$src"
[ -n "$MC" ] && echo "meshcheck: $MC; fixed: $MCF"
exit 0
