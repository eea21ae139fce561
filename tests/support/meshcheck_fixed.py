#!/usr/bin/env python3
"""Copies ../shared's meshcheck source to OUT and applies five fixes for floating-point artefacts
it shows on slanted facets and at scales below its tolerance (see docs/benchmarks.md, "meshcheck
on slanted facets", and the seventy-first part):

1. A face whose share of a coplanar facet is a rounding sliver (within 1e-9 of the face plus fix
   3's slack) does not make the face span that facet: the sliver still counts towards the facet's
   coverage, but the face is "inside one facet but for a sliver". Without this a face inside one facet
   with a vertex rounded 1e-17 across the common edge with a coplanar facet of another marker (a
   split point of that edge: no double point lies exactly on a slanted edge) is reported as
   "spanning coplanar facets of different markers", while the same sliver beyond an edge with no
   coplanar neighbour is accepted as "rounded".
2. clippedArea clips in coordinates relative to the face's first vertex instead of absolute ones:
   a face of area 1e-7 at coordinates 300 lost its area to cancellation.
3. The tolerance on a face's shares (and on a facet's coverage, summed over its faces) adds what
   rounding of the vertices alone can do: 8 ulps of the face's largest coordinate times its
   perimeter. A thin face (1e-3 by 2e-5) at coordinates 280 whose vertex is rounded one ulp off a
   slanted edge leaves its facet by a sliver of 2e-9 of its area, over the relative 1e-9 alone.
   The library verifier uses the same slack (modules/verify, rounding_slack).
4. A mesh vertex counts as near a facet when it lies within 8 ulps of its largest coordinate of an
   edge of the facet, in 3D, even if its projection falls just outside the facet's region. Without
   this a Steiner point on a slanted edge between two facets at 176 degrees, rounded 7e-15 across
   the edge (coordinates 280), lies in neither facet's projected region, is classed as on no facet,
   and every face at it is reported as "on no input facet" (occ_pump_nut at --quality 1.414). The
   face's area shares still decide whether it leaves the facet.
5. A face lies in an exactly planar facet's plane only if its vertices are within 1e-5 of its
   width (its least altitude) of the plane (or within 8192 ulps of its largest coordinate), besides
   each within the tolerance. OpenSCAD's example010 (a model 70 across, tolerance 7e-8) is
   conformed with cells of 6e-8 next to a facet of area 3.5e-6: their faces through a point 5.9e-8
   off the facet counted as on it, and the facet as covered more than once. The library verifier
   applies the same test.

Every fix asserts the text it replaces, so a changed meshcheck stops this script instead of being
patched blindly. Files already in OUT with the same content are not rewritten (no rebuild).
usage: meshcheck_fixed.py SHARED_MESHCHECK_DIR OUT_DIR
"""
import os
import sys

src, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)


def put(name, data):
    path = os.path.join(out, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if os.path.exists(path) and open(path, "rb").read() == data:
        return
    with open(path, "wb") as f:
        f.write(data)
    os.chmod(path, 0o755 if name.endswith(".sh") else 0o644)


for name in ("CMakeLists.txt", "build.sh", "README.md"):
    put(name, open(os.path.join(src, name), "rb").read())
# meshcheck's own hand-made cases (tests/run.sh builds with ../build.sh and asserts each verdict):
# the test meshcheck_fixed_cases runs them on the fixed copy, so the fixes cannot pass a case
# meshcheck as shipped fails
tests = os.path.join(src, "tests")
if os.path.isdir(tests):
    for name in sorted(os.listdir(tests)):
        if os.path.isfile(os.path.join(tests, name)):
            put(os.path.join("tests", name), open(os.path.join(tests, name), "rb").read())
text = open(os.path.join(src, "meshcheck.cpp")).read()
fixes = [
    ("""  Poly tri;
  for (int i = 0; i < 3; ++i) {
    P2 q = project(t[i], f.axis);
    tri.push_back({q.x(), q.y()});
  }""",
     """  Poly tri;
  const P2 o = project(t[0], f.axis);  // gsse fix 2: relative to the face's first vertex
  for (int i = 0; i < 3; ++i) {
    P2 q = project(t[i], f.axis);
    tri.push_back({q.x() - o.x(), q.y() - o.y()});
  }"""),
    ("      const P2 &a = fh->vertex(i)->point(), &b = fh->vertex((i + 1) % 3)->point();",
     """      const P2 a(fh->vertex(i)->point().x() - o.x(), fh->vertex(i)->point().y() - o.y());  // gsse fix 2
      const P2 b(fh->vertex((i + 1) % 3)->point().x() - o.x(), fh->vertex((i + 1) % 3)->point().y() - o.y());"""),
]
slack = """// gsse fix 3: what rounding of the vertices alone can do to a face's shares
static double roundingSlack(const Mesh& m, const uint32_t* v) {
  double mag = 0, perimeter = 0;
  for (int t = 0; t < m.dim; ++t) {
    for (int a = 0; a < 3; ++a) mag = std::max(mag, std::fabs(m.pts[v[t]][a]));
    if (m.dim == 3 || t == 0) perimeter += norm(sub(m.pts[v[t]], m.pts[v[(t + 1) % m.dim]]));
  }
  const double eps = std::numeric_limits<double>::epsilon();
  return m.dim == 3 ? 8 * eps * mag * perimeter : 8 * eps * mag;
}

Placement placeFace("""
fixes += [
    ("""Placement placeFace(""", slack),
    ("""  if (!hits.empty() && std::fabs(covered - size) <= kRelTol * size)
    return hits.size() > 1 ? Placement::kSpanning : Placement::kRounded;""",
     """  if (!hits.empty() && std::fabs(covered - size) <= kRelTol * size + roundingSlack(m, v)) {  // gsse fix 3
    // gsse fix 1: every share covers its facet, but only shares beyond rounding decide where the
    // face lies; a sliver takes the marker of the face's main facet (no span of markers)
    const double slack = kRelTol * size + roundingSlack(m, v);
    size_t mainHit = 0, significant = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
      if (hits[i].share > hits[mainHit].share) mainHit = i;
      if (hits[i].share > slack) ++significant;
    }
    for (FacetHit& h : hits)
      if (h.share <= slack) h.marker = hits[mainHit].marker;
    return significant > 1 ? Placement::kSpanning : Placement::kRounded;
  }"""),
    ("""  double hullFlux = 0;   // divergence-theorem volume term of those hull faces
};""",
     """  double hullFlux = 0;   // divergence-theorem volume term of those hull faces
  double slack = 0;      // gsse fix 3: rounding slack of the faces on it, relative to its size
};"""),
    ("""      cv.all += h.share;
      if (bounding) cv.bounding += h.share;""",
     """      cv.all += h.share;
      cv.slack += roundingSlack(m, v) / plc.facets[h.facet].size;  // gsse fix 3
      if (bounding) cv.bounding += h.share;"""),
    ("""    if (err > kRelTol) {
      overcovered""", """    if (err > kRelTol + cv.slack) {  // gsse fix 3
      overcovered"""),
    ("""      if (std::fabs(err) <= kRelTol) ++boundingCovered;""",
     """      if (std::fabs(err) <= kRelTol + cv.slack) ++boundingCovered;  // gsse fix 3"""),
    ("""      if (std::fabs(err) <= kRelTol) ++internalRespected;""",
     """      if (std::fabs(err) <= kRelTol + cv.slack) ++internalRespected;  // gsse fix 3"""),
]
fixes += [
    ("""enum On { kOff = 0, kNear = 1, kExact = 2 };""",
     """enum On { kOff = 0, kNear = 1, kExact = 2 };

// gsse fix 4: whether p lies within what rounding of a coordinate can do (8 ulps of the largest
// magnitude involved) of an edge of facet f, in 3D
static bool nearFacetBoundary(const Plc& plc, const Facet& f, const Vec& p) {
  for (const auto& poly : f.polys)
    for (size_t k = 0; poly.size() > 1 && k < poly.size(); ++k) {
      if (poly.size() == 2 && k == 1) break;
      const Vec &a = plc.pts[poly[k]], &b = plc.pts[poly[(k + 1) % poly.size()]];
      double mag = 0;
      for (int i = 0; i < 3; ++i) mag = std::max({mag, std::fabs(p[i]), std::fabs(a[i]), std::fabs(b[i])});
      const Vec d = sub(b, a);
      const double len2 = dot(d, d);
      const double t = len2 > 0 ? std::clamp(dot(sub(p, a), d) / len2, 0.0, 1.0) : 0.0;
      const Vec c{a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]};
      if (norm(sub(p, c)) <= 8 * std::numeric_limits<double>::epsilon() * mag) return true;
    }
  return false;
}"""),
    ("""  if (!inFacetRegion(f, v)) return kOff;
  return coplanar ? kExact : kNear;""",
     """  if (!inFacetRegion(f, v)) return nearFacetBoundary(plc, f, v) ? kNear : kOff;  // gsse fix 4
  return coplanar ? kExact : kNear;"""),
]
fixes += [
    ("""Placement placeFace(""",
     """// gsse fix 5: a face lies in a facet's plane only if its vertices are within 1e-5 of its width (3D:
// least altitude) of that plane (or within rounding of it: 8192 ulps of the largest coordinate),
// besides each within the tolerance: a face far smaller or thinner than the tolerance (a cell of
// 6e-8 next to a facet of 1e-4 in a model 70 across) otherwise counts as on the facet. Facets not
// exactly planar keep the tolerance alone. The library verifier applies the same test
// (modules/verify, face_in_plane)
static bool faceInPlane(const Plc& plc, const Facet& f, const Mesh& m, const uint32_t* v) {
  if (!f.exactPlanar) return true;
  const Vec& a = plc.pts[f.plane[0]];
  double longest = 0, far = 0, mag = 0;
  for (int t = 0; t < m.dim; ++t) {
    longest = std::max(longest, norm(sub(m.pts[v[t]], m.pts[v[(t + 1) % m.dim]])));
    far = std::max(far, std::fabs(dot(sub(m.pts[v[t]], a), f.unitNormal)));
    for (int i = 0; i < 3; ++i) mag = std::max({mag, std::fabs(m.pts[v[t]][i]), std::fabs(a[i])});
  }
  double width = longest;  // 3D: the least altitude, twice the area over the longest edge
  if (m.dim == 3 && longest > 0)
    width = norm(cross(sub(m.pts[v[1]], m.pts[v[0]]), sub(m.pts[v[2]], m.pts[v[0]]))) / longest;
  else if (m.dim == 3)
    width = 0;
  return far <= std::max(1e-5 * width, 8192 * std::numeric_limits<double>::epsilon() * mag);
}

Placement placeFace("""),
    ("""    if (all && (k == 2 || inFacetRegion(plc.facets[cand[c]], centroid)))""",
     """    if (all && (exact || faceInPlane(plc, plc.facets[cand[c]], m, v)) &&  // gsse fix 5
        (k == 2 || inFacetRegion(plc.facets[cand[c]], centroid)))"""),
    ("""    if (!coplanar) continue;""",
     """    if (!coplanar || (!exact && !faceInPlane(plc, f, m, v))) continue;  // gsse fix 5"""),
]
for old, new in fixes:
    if text.count(old) != 1:
        sys.exit("meshcheck_fixed.py: meshcheck.cpp changed, cannot apply: " + old.splitlines()[0].strip())
    text = text.replace(old, new)
put("meshcheck.cpp", text.encode())
