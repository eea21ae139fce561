#!/usr/bin/env bash
# Bad input: every case must exit non-zero, print an error naming the file (and line or entity),
# and leave no output file behind.
set -uo pipefail
mesh=$1; src=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail=0; n=0
expect() {  # file expected-substring [extra args]
  local in=$1 want=$2; shift 2
  local out=$work/out.vtu; rm -f "$out"
  local msg; msg=$(timeout "${limit:-60}" "$mesh" "$in" -o "$out" --quiet "$@" 2>&1); local rc=$?
  n=$((n + 1))
  if [ $rc -eq 0 ] || [ $rc -ge 124 ]; then echo "FAIL: $in: exit $rc"; fail=1
  elif [[ "$msg" != *"$want"* ]]; then echo "FAIL: $in: message '$msg' lacks '$want'"; fail=1
  elif [ -e "$out" ] || ls "$work"/.out.vtu* >/dev/null 2>&1; then echo "FAIL: $in: output left behind"; fail=1
  else echo "ok: $(basename "$in"): $msg"; fi
}
cube() {  # writes a unit cube .poly with optional edits via sed
  cat > "$1" <<'P'
8 3 0 0
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0 0 1
6 1 0 1
7 1 1 1
8 0 1 1
6 0
1
4 1 2 3 4
1
4 5 6 7 8
1
4 1 2 6 5
1
4 2 3 7 6
1
4 3 4 8 7
1
4 4 1 5 8
0
1
1 0.5 0.5 0.5 1 -1
P
}
cube "$work/ok.poly"
"$mesh" "$work/ok.poly" --quiet -o "$work/ok.vtu" || { echo "FAIL: the valid cube does not mesh"; fail=1; }
cube "$work/nan.poly"; sed -i 's/^3 1 1 0$/3 1 nan 0/' "$work/nan.poly"; expect "$work/nan.poly" "nan.poly:4: 'nan' is not a finite number"
cube "$work/dup.poly"; sed -i 's/^8 0 1 1$/8 1 1 1/' "$work/dup.poly"; expect "$work/dup.poly" "duplicate point: point 8 repeats point 7"
cube "$work/range.poly"; sed -i 's/^4 4 1 5 8$/4 4 1 5 9/' "$work/range.poly"; expect "$work/range.poly" "corner 9 out of range"
cube "$work/open.poly"; python3 - "$work/open.poly" <<'PY'
import sys; p=sys.argv[1]; l=open(p).read().split('\n'); i=l.index('4 4 1 5 8'); del l[i-1:i+1]; l[l.index('6 0')]='5 0'; open(p,'w').write('\n'.join(l))
PY
expect "$work/open.poly" "not closed"
cube "$work/outside.poly"; sed -i 's/^1 0.5 0.5 0.5 1 -1$/1 5 5 5 1 -1/' "$work/outside.poly"; expect "$work/outside.poly" "outside the domain"
cube "$work/trunc.poly"; head -12 "$work/ok.poly" > "$work/trunc.poly"; expect "$work/trunc.poly" "unexpected end of file"
cube "$work/bend.poly"; sed -i 's/^8 0 1 1$/8 0 1 1.5/' "$work/bend.poly"; expect "$work/bend.poly" "not in the facet's plane"
# self-intersecting PLCs are found before meshing (the conformer would refine them forever)
boxes() {  # file, then boxes "x0 y0 z0 x1 y1 z1" (facets as in cube()) or quads "x y z" x 4; one region
  local f=$1; shift
  python3 - "$f" "$@" <<'PY'
import sys
f, pts, fac = sys.argv[1], [], []
for arg in sys.argv[2:]:
    l, b = list(map(float, arg.split())), len(pts)
    if len(l) == 6:
        pts += [(l[0], l[1], l[2]), (l[3], l[1], l[2]), (l[3], l[4], l[2]), (l[0], l[4], l[2]),
                (l[0], l[1], l[5]), (l[3], l[1], l[5]), (l[3], l[4], l[5]), (l[0], l[4], l[5])]
        fac += [[b + i for i in q] for q in ((1, 2, 3, 4), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8))]
    else:
        pts += [tuple(l[i:i + 3]) for i in range(0, 12, 3)]
        fac.append([b + 1, b + 2, b + 3, b + 4])
with open(f, "w") as o:
    o.write(f"{len(pts)} 3 0 0\n" + "".join(f"{i + 1} {x:g} {y:g} {z:g}\n" for i, (x, y, z) in enumerate(pts)))
    o.write(f"{len(fac)} 0\n" + "".join("1\n4 " + " ".join(map(str, q)) + "\n" for q in fac))
    o.write("0\n1\n1 0.25 0.25 0.25 1 -1\n")
PY
}
boxes "$work/pierce.poly" "0 0 0 1 1 1" "0.5 0.25 0.5  0.5 0.75 0.5  0.5 0.75 1.5  0.5 0.25 1.5"
limit=10 expect "$work/pierce.poly" "pierce.poly:27: facet 7 (line 27) intersects facet 2 (line 17): they cross"
boxes "$work/overlap.poly" "0 0 0 1 1 1" "0.5 0.5 0.5 1.5 1.5 1.5"
limit=10 expect "$work/overlap.poly" "overlap.poly:35: facet 9 (line 35) intersects facet 2 (line 21): they cross (and 5 more)"
printf '4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n6 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n5 1 3\n6 2 4\n0\n' > "$work/cross2d.poly"
limit=10 expect "$work/cross2d.poly" "cross2d.poly: segment 6 (vertices 2-4) intersects segment 5 (vertices 1-3): they cross"
expect "$work/missing.poly" "cannot open file"
expect "$work/ok.poly" "unknown option" --frobnicate
expect "$work/ok.poly" "--size must be positive" --size -1
printf '2 3 0 0\n1 0.5 0.5 0.5\n2 0.5 0.5 0.5\n' > "$work/cloud.node"; expect "$work/ok.poly" "duplicate point" --cloud "$work/cloud.node"
printf 'dimension 3\nsplit x\n element subfacet\nend\n' > "$work/bad.rules"; expect "$work/ok.poly" "bad.rules:2: split rule 'x': missing 'relation'" --rules "$work/bad.rules"
expect "$work/ok.poly" "a 2D rule set for a 3D input" --rules "$src/rules/conformer2d.rules"
expect "$work/ok.poly" "--threads must be a whole number from 1 to 4096, not '-1'" --threads -1
expect "$work/ok.poly" "--threads must be a whole number from 1 to 4096, not '0'" --threads 0
expect "$work/ok.poly" "--msh must be 4.1 or 2.2, not '3'" --msh 3
mkdir "$work/ok.json"; expect "$work/ok.poly" "ok.json: cannot read the sidecar file"; rmdir "$work/ok.json"
# an unknown output format is refused before meshing (this size would take minutes to mesh)
n=$((n + 1))
t0=$(date +%s%N); msg=$(timeout 60 "$mesh" "$work/ok.poly" --size 0.002 -o "$work/x.obj" --quiet 2>&1); rc=$?
ms=$((($(date +%s%N) - t0) / 1000000))
if [ $rc -eq 0 ] || [[ "$msg" != *"unknown output format '.obj'"* ]] || [ $ms -gt 5000 ] || [ -e "$work/x.obj" ]; then
  echo "FAIL: unknown output format: exit $rc after $ms ms: $msg"; fail=1
else echo "ok: unknown output format refused in $ms ms: ${msg%%$'\n'*}"; fi
# the conformer's trace goes through the CLI: on with GSSE_CONFORM_TRACE=1, off with 0 or unset
n=$((n + 1))
on=$(GSSE_CONFORM_TRACE=1 "$mesh" "$work/ok.poly" --quiet 2>&1 | grep -c "^conform round")
off=$(GSSE_CONFORM_TRACE=0 "$mesh" "$work/ok.poly" --quiet 2>&1 | grep -c "^conform round")
unset_=$(env -u GSSE_CONFORM_TRACE "$mesh" "$work/ok.poly" --quiet 2>&1 | grep -c "^conform round")
if [ "$on" -ge 1 ] && [ "$off" = 0 ] && [ "$unset_" = 0 ]; then echo "ok: trace: $on round lines with GSSE_CONFORM_TRACE=1, none with 0 or unset"
else echo "FAIL: trace lines: $on with 1, $off with 0, $unset_ unset"; fail=1; fi
[ $fail = 0 ] && echo "$n passed, 0 failed" || echo "some cases FAILED"
exit $fail
