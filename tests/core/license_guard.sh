#!/usr/bin/env bash
# The library and the CLI are compiled with CGAL_LICENSE_ERROR, so that no GPL CGAL package can be
# included into them (only the tests and benchmarks may use CGAL's GPL triangulations):
#  1. every compile command of rules/, modules/ and apps/ in compile_commands.json defines it;
#  2. with it, including a GPL package (Triangulation_3) fails to compile, and an LGPL one
#     (the kernel's predicates) compiles: the guard works on this CGAL.
# usage: license_guard.sh BUILD_DIR SOURCE_DIR CXX
set -u
build=$1 src=$2 cxx=$3
db=$build/compile_commands.json
[ -f "$db" ] || { echo "FAIL: $db missing (CMAKE_EXPORT_COMPILE_COMMANDS)"; exit 1; }
/usr/bin/python3 - "$db" "$src" <<'PY' || exit 1
import json, sys
db, src = json.load(open(sys.argv[1])), sys.argv[2]
mine = [e for e in db if any(e["file"].startswith(f"{src}/{d}/") for d in ("rules", "modules", "apps"))]
bad = [e["file"] for e in mine if "-DCGAL_LICENSE_ERROR" not in e.get("command", " ".join(e.get("arguments", [])))]
print(f"{len(mine)} library and CLI sources, {len(bad)} without CGAL_LICENSE_ERROR {bad[:5]}")
sys.exit(1 if bad or not mine else 0)
PY
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
printf '#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>\n#include <CGAL/Delaunay_triangulation_3.h>\nint main() {}\n' > "$tmp/gpl.cpp"
printf '#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>\nint main() { CGAL::Epick::Point_3 p(0, 0, 0); return CGAL::orientation(p, p, p, p) == CGAL::COPLANAR ? 0 : 1; }\n' > "$tmp/lgpl.cpp"
if "$cxx" -std=c++20 -fsyntax-only -DCGAL_LICENSE_ERROR=1 "$tmp/gpl.cpp" 2> "$tmp/err"; then
  echo "FAIL: a GPL CGAL package compiled with CGAL_LICENSE_ERROR"; exit 1
fi
grep -q "CGAL_LICENSE_ERROR" "$tmp/err" || { echo "FAIL: the GPL include failed for another reason:"; head -5 "$tmp/err"; exit 1; }
"$cxx" -std=c++20 -fsyntax-only -DCGAL_LICENSE_ERROR=1 "$tmp/lgpl.cpp" || { echo "FAIL: the kernel does not compile with the guard"; exit 1; }
echo "ok: GPL include refused, LGPL kernel accepted"
