#include "gsse/pipeline/pipeline.hpp"
#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/dihedral.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <tuple>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <memory>
#include <set>
#include <span>
#include <type_traits>

#include "gsse/container/union_find.hpp"
#include "gsse/front/front_mesher.hpp"
#include "gsse/front/gift_wrap.hpp"
#include "gsse/geometry/hash_grid.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/location/locator.hpp"
#include "gsse/plc/intersections.hpp"
#include "gsse/sizing/distance.hpp"
#include "gsse/sizing/place_points.hpp"
#include "gsse/rules/defaults.hpp"
#include "gsse/topology/incidence.hpp"
#include "gsse/traversal/for_each.hpp"
#include "gsse/traversal/parallel_sort.hpp"
#include "gsse/verify/verify.hpp"

namespace gsse::pipeline {
namespace {

template <std::size_t D>
using cell_t = std::array<vertex_id, D + 1>;

/// Faces of every region, each oriented with its region on the positive side, in face order: one
/// pass over the faces (not one per region).
template <std::size_t D>
std::vector<std::vector<std::array<vertex_id, D>>> region_boundaries(const conformer::boundary<D>& b,
                                                                      const conformer::labelling& l) {
  std::vector<std::vector<std::array<vertex_id, D>>> out(l.regions.size());
  for (std::size_t f = 0; f < b.faces.size(); ++f)
    for (int s = 0; s < 2; ++s)
      if (const int r = l.side[f][static_cast<std::size_t>(s)]; r >= 0 && static_cast<std::size_t>(r) < out.size()) {
        auto F = b.faces[f];
        if (s == 1) std::swap(F[0], F[1]);
        out[static_cast<std::size_t>(r)].push_back(F);
      }
  return out;
}

inline std::string region_label(const conformer::labelling& l, std::size_t r) {
  return "segment " + std::to_string(l.regions[r].number) + " '" + l.regions[r].name + "'";
}

/// How often a region is halved before meshing (DeWall walls): until its pieces hold about an
/// eighth of the domain's volume or less, so that a dominant region (the substrate) keeps every
/// thread busy. Depends on the input only, never on the thread count, so the cell order, hence
/// the output, is the same for any N.
template <std::size_t D>
std::vector<int> split_depths(const std::vector<point<D>>& pts, const std::vector<std::vector<std::array<vertex_id, D>>>& bnd) {
  std::vector<double> vol(bnd.size(), 0);
  double total = 0;
  for (std::size_t r = 0; r < bnd.size(); ++r) {
    for (const auto& f : bnd[r]) {  // divergence theorem; faces face into the region
      if constexpr (D == 2)
        vol[r] += pts[f[0]][0] * pts[f[1]][1] - pts[f[1]][0] * pts[f[0]][1];
      else
        vol[r] += dot(pts[f[0]], cross(pts[f[1]], pts[f[2]]));
    }
    vol[r] = std::abs(vol[r]);
    total += vol[r];
  }
  std::vector<int> depth(bnd.size(), 0);
  // small meshes: not worth a wall (from 4,000 points: at 20,000 the 1e5-tetrahedron MOSFET's
  // substrate, 18,000 points, kept one thread busy while the other idled; docs/benchmarks.md)
  if (pts.size() < 4000 || !(total > 0)) return depth;
  for (std::size_t r = 0; r < bnd.size(); ++r)
    while (depth[r] < 4 && vol[r] > total / 8 * static_cast<double>(1 << depth[r])) ++depth[r];
  return depth;
}

template <std::size_t D>
using pieces_t = std::vector<std::vector<std::vector<cell_t<D>>>>;  // region -> its cells, in pieces

/// Cells of every region, meshed in parallel with the points `pts` (b.points, possibly extended).
/// Large regions are first split by walls across the longest side of their bounding box; the
/// pieces are then meshed as regions of their own. Pieces are tasks taken by free threads, largest
/// first (walls before all, since they make the next tasks); each region's pieces are ordered by
/// level of the split tree, then by position within it, whatever the threads did.
template <std::size_t D>
pieces_t<D> wrap_pieces(const std::vector<point<D>>& pts, const conformer::boundary<D>& b,
                        const conformer::labelling& l, unsigned threads) {
  using face = std::array<vertex_id, D>;
  const auto grid = front::make_grid(std::span<const point<D>>(pts));
  auto bnd = region_boundaries(b, l);
  const auto depth = split_depths(pts, bnd);
  struct piece {
    std::size_t region;
    std::vector<face> front;
    int depth;                // walls still to build above the leaves
    int level;                // in the split tree
    std::uint64_t index;      // position within the level (binary path: side 0 -> 2i, side 1 -> 2i+1)
  };
  struct result {
    int level;
    std::uint64_t index;
    std::vector<cell_t<D>> cells;
  };
  std::vector<piece> todo;
  for (std::size_t r = 0; r < l.regions.size(); ++r) todo.push_back({r, std::move(bnd[r]), depth[r], 0, 0});
  std::vector<std::vector<result>> done(l.regions.size());
  std::mutex m;
  std::condition_variable cv;
  std::size_t busy = 0;
  std::exception_ptr error;
  auto process = [&](piece& pc, std::array<std::vector<face>, 2>& sides) {
    if (pc.depth == 0) return front::wrap(std::span<const point<D>>(pts), grid, pc.front, region_label(l, pc.region));
    point<D> lo = pts[pc.front[0][0]], hi = lo;
    for (const auto& f : pc.front)
      for (auto v : f)
        for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], pts[v][k]), hi[k] = std::max(hi[k], pts[v][k]);
    std::size_t axis = 0;
    for (std::size_t k = 1; k < D; ++k)
      if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    return front::wrap_wall(std::span<const point<D>>(pts), grid, pc.front, region_label(l, pc.region), axis,
                            0.5 * (lo[axis] + hi[axis]), sides);
  };
  auto worker = [&] {
    std::unique_lock lock(m);
    for (;;) {
      cv.wait(lock, [&] { return !todo.empty() || busy == 0 || error; });
      if (todo.empty() || error) break;  // nothing left, or nothing can come
      // walls first (they make work), then whole regions, then the pieces of split ones, each
      // by the largest front: a region's cost per face varies (up to twice as much in a thin
      // layer, whose searches reach into its neighbours), so whole regions go while walls are built and
      // the pieces, of like size (walls halve them), fill the end evenly
      auto rank = [](const piece& x) { return std::tuple(x.depth > 0, x.level == 0, x.front.size()); };
      auto it = std::max_element(todo.begin(), todo.end(), [&](const piece& x, const piece& y) { return rank(x) < rank(y); });
      piece pc = std::move(*it);
      todo.erase(it);
      ++busy;
      lock.unlock();
      std::array<std::vector<face>, 2> sides;
      std::vector<cell_t<D>> cells;
      std::exception_ptr e;
      try {
        cells = process(pc, sides);
      } catch (...) {
        e = std::current_exception();
      }
      lock.lock();
      --busy;
      if (e && !error) error = e;
      done[pc.region].push_back({pc.level, pc.index, std::move(cells)});
      for (std::size_t k = 0; k < 2; ++k)
        if (!sides[k].empty())
          todo.push_back({pc.region, std::move(sides[k]), pc.depth - 1, pc.level + 1, 2 * pc.index + k});
      cv.notify_all();
    }
  };
  // one worker per thread, on the library's pool (for_each): each takes pieces until none is
  // left or can come; a worker the pool cannot staff at once finds the work done and returns
  std::vector<unsigned> workers(execution::thread_count(threads));
  for_each(execution::par(threads), workers, [&](unsigned) { worker(); });
  if (error) std::rethrow_exception(error);
  pieces_t<D> cells(l.regions.size());
  for (std::size_t r = 0; r < done.size(); ++r) {
    auto& rs = done[r];
    std::sort(rs.begin(), rs.end(), [](const result& x, const result& y) { return std::pair(x.level, x.index) < std::pair(y.level, y.index); });
    for (auto& x : rs) cells[r].push_back(std::move(x.cells));
  }
  return cells;
}

/// Regions meshed with rule-driven point creation, each on its own copy of the points; the
/// created points are appended to `pts` (a copy of b.points) region by region, then every region
/// is meshed again with all of them.
template <std::size_t D>
pieces_t<D> wrap_all_creating(std::vector<point<D>>& pts, const conformer::boundary<D>& b,
                                                      const conformer::labelling& l, unsigned threads,
                                                      const front::creation_options& co, front::creation_stats& cs) {
  pts = b.points;
  const auto grid = front::make_grid(std::span<const point<D>>(b.points));
  const front::boundary_faces<D> faces(std::span<const point<D>>(b.points), std::span<const std::array<vertex_id, D>>(b.faces));
  std::vector<std::vector<point<D>>> created(l.regions.size());
  std::vector<front::creation_stats> st(l.regions.size());
  std::vector<std::size_t> ids(l.regions.size());
  std::iota(ids.begin(), ids.end(), 0);
  const auto bnd = region_boundaries(b, l);
  auto work = [&](std::size_t r) {
    std::vector<point<D>> own = b.points;
    front::wrap_creating(own, grid, faces, bnd[r], region_label(l, r), co, &st[r]);
    created[r].assign(own.begin() + static_cast<std::ptrdiff_t>(b.points.size()), own.end());
  };
  for_each(execution::par(threads), ids, work, [&](std::size_t r) { return static_cast<double>(bnd[r].size()); });
  for (std::size_t r = 0; r < l.regions.size(); ++r) {
    cs += st[r];
    pts.insert(pts.end(), created[r].begin(), created[r].end());
  }
  return wrap_pieces(pts, b, l, threads);
}

/// The unsized conformed boundary (PLC facets, conformed, no size splits) and a coarse mesh of
/// it: it bounds the same surface as the sized boundary at a fraction of the cost, and locates
/// points exactly (modules/location) for the interior point placement and the size field. A
/// point on the PLC counts as inside (the closed cells): the conformer makes it a boundary vertex.
template <std::size_t D>
struct coarse_model {
  conformer::boundary<D> b;
  conformer::labelling l;
  location::locator<D> at;

  coarse_model(const plc<D>& p, const conformer::options& co) {
    conformer::options unsized = co;
    unsized.size = 0;
    unsized.local_size2 = nullptr;
    unsized.local_size3 = nullptr;
    b = conformer::conform(p, {}, unsized);
    l = conformer::label(b, p, co.threads);
    std::vector<std::vector<cell_t<D>>> cells;
    for (const auto& region : wrap_pieces(b.points, b, l, co.threads)) {
      cells.emplace_back();
      for (const auto& cs : region) cells.back().insert(cells.back().end(), cs.begin(), cs.end());
    }
    at = location::locator<D>(b.points, cells);
  }
};

/// The user's cloud points that lie in a segment appended to `out` (the others counted in
/// `dropped`), then duplicates removed (a cloud point may repeat a lattice point or another one).
template <std::size_t D>
void add_cloud(std::vector<point<D>>& out, const std::vector<point<D>>& cloud, const coarse_model<D>& m,
               std::size_t& dropped, unsigned threads) {
  for (const auto& q : cloud) {
    if (m.at.in_segment(q))
      out.push_back(q);
    else
      ++dropped;
  }
  gsse::stable_sort(execution::par(threads), out.begin(), out.end(), [](const auto& x, const auto& y) { return lex_less(x, y); });
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

/// Points of the size field `h` (graded placement, modules/sizing) plus the cloud.
template <std::size_t D>
std::vector<point<D>> field_points(const coarse_model<D>& m, const sizing::size_field<D>& h,
                                   const std::vector<point<D>>& cloud, std::size_t& dropped, unsigned threads) {
  const auto& b = m.b;
  std::vector<sizing::aabb<D>> fb(b.faces.size());
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    fb[f] = sizing::aabb<D>::empty();
    for (vertex_id v : b.faces[f]) fb[f].add(b.points[v]);
  }
  const sizing::box_tree<D> faces(std::move(fb), std::vector<double>(b.faces.size(), 0.0));
  sizing::placement<D> where;
  where.segment_of = [&](const point<D>& q) {
    thread_local std::uint32_t hint = location::locator<D>::no_cell;  // per worker: its last cell (region_of)
    const int r = m.at.region_of(q, hint);
    return r < 0 ? sizing::no_segment : m.l.regions[static_cast<std::size_t>(r)].number;
  };
  where.clear = [&](const point<D>& q, double keep) {
    return faces.visit([&](const sizing::aabb<D>& bx) { return bx.distance2(q) < keep * keep; }, [&](std::uint32_t f) {
      std::array<point<D>, D> F;
      for (std::size_t i = 0; i < D; ++i) F[i] = b.points[b.faces[f][i]];
      return sizing::face_distance2<D>(F, q) >= keep * keep;
    });
  };
  auto out = sizing::place_points<D>(h, sizing::aabb<D>{m.at.lo(), m.at.hi()}, where, threads);
  add_cloud(out, cloud, m, dropped, threads);
  return out;
}

/// Lattice points about h apart (see size_points) plus the cloud.
template <std::size_t D>
std::vector<point<D>> lattice_points(const coarse_model<D>& m, double h, const std::vector<point<D>>& cloud,
                                     std::size_t& dropped, unsigned threads, bool lattice) {
  const auto& b = m.b;
  const point<D> lo = m.at.lo(), hi = m.at.hi();
  auto in_segment = [&](const point<D>& q, std::uint32_t& hint) { return m.at.in_segment(q, hint); };
  conformer::options co;
  co.threads = threads;
  std::vector<point<D>> out;
  if (h > 0 && lattice) {
    // keep-off distance from the boundary faces (not only their vertices: a lattice point close to
    // a facet's interior would be projected onto it, leaving a very short edge), through a hash
    // of the faces' bounding boxes; double distances only place points, they decide no topology
    // (a hair over half the lattice's neighbour distance h: two neighbours both this far from
    // every face have no face between them, so the segment test below is asked once per
    // connected set of clear points; 1e-7 covers the rounding of positions and distances)
    const double keep = 0.5 * h * (1 + 1e-7);
    hash_grid<D> near(lo, keep);
    using cell = typename hash_grid<D>::cell;
    auto face_distance2 = [&](std::uint32_t f, const point<D>& q) {
      const auto& F = b.faces[f];
      if constexpr (D == 2) {
        return sizing::segment_distance2(b.points[F[0]], b.points[F[1]], q);
      } else {
        // closest point of the triangle: the plane's foot if inside, else the nearest edge point
        return sizing::triangle_distance2(b.points[F[0]], b.points[F[1]], b.points[F[2]], q);
      }
    };
    // the hash's cells over the model's box: a dense map of them is kept where it is small
    std::array<long, D> dims{};
    double cells_total = 1;
    for (std::size_t k = 0; k < D; ++k) {
      dims[k] = static_cast<long>((hi[k] - lo[k]) / keep) + 1;
      cells_total *= static_cast<double>(dims[k]);
      if (dims[k] >= (1l << 20)) cells_total = 1e300;
    }
    // a cell clamped into the dense map: a face in a cell within one cell of q's lies within one
    // cell of q's clamped cell too (clamping keeps the order of coordinates and shortens gaps)
    auto index_of = [&](const cell& c) {
      std::size_t i = 0;
      for (std::size_t k = D; k-- > 0;) i = i * static_cast<std::size_t>(dims[k]) + static_cast<std::size_t>(std::clamp(c[k], 0l, dims[k] - 1));
      return i;
    };
    // each face's cells (not its box: a slanted facet's box is a volume of cells), listed in
    // parallel. Up to 2^24 cells they are filed in a dense table (faces per cell, counted then
    // filled in face order), else in the hash: filing 467,000 (cell, face) pairs one by one into
    // the hash, a vector per cell, was 40 ms of serial work on the rotated trench at 6e5 elements
    std::vector<std::vector<cell>> face_cells(b.faces.size());
    {
      std::vector<std::uint32_t> face_ids(b.faces.size());
      std::iota(face_ids.begin(), face_ids.end(), std::uint32_t{0});
      // largest first: a face's cells grow with its extent (to the power D - 1)
      for_each(execution::par(threads), face_ids, [&](std::uint32_t f) {
        std::array<point<D>, D> v;
        for (std::size_t k = 0; k < D; ++k) v[k] = b.points[b.faces[f][k]];
        near.simplex_cells(v, [&](const cell& c) { face_cells[f].push_back(c); });
      }, [&](std::uint32_t f) {
        double e = 0;
        for (std::size_t k = 1; k < D; ++k) e = std::max(e, distance(b.points[b.faces[f][0]], b.points[b.faces[f][k]]));
        return std::pow(e / keep + 1, static_cast<double>(D - 1));
      });
    }
    const bool dense = cells_total <= double(1 << 24);
    std::vector<std::uint32_t> first, listed;  // dense: the faces of cell i are listed[first[i] .. first[i + 1])
    if (dense) {
      first.assign(static_cast<std::size_t>(cells_total) + 1, 0);
      for (const auto& cs : face_cells)
        for (const auto& c : cs) ++first[index_of(c) + 1];
      for (std::size_t i = 1; i < first.size(); ++i) first[i] += first[i - 1];
      listed.resize(first.back());
      std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
      for (std::uint32_t f = 0; f < face_cells.size(); ++f)
        for (const auto& c : face_cells[f]) listed[fill[index_of(c)]++] = f;
    } else {
      for (std::uint32_t f = 0; f < face_cells.size(); ++f)
        for (const auto& c : face_cells[f]) near.insert_cell(f, c);
    }
    face_cells = {};
    // a dense map of the cells the ring search below can find a face from (within one cell of an
    // occupied one): a lattice point in an unmarked cell is clear without a look at the faces
    // (most of a slanted model's bounding box is far from every face, and each look reads the 3^D
    // cells about the point). Marked from the faces' own cells, not their boxes (a slanted face's
    // box is a volume of cells: on the rotated structures most cells were marked), so a point is
    // unmarked exactly when the ring search would find no face. Skipped above 2^26 cells or 2^20
    // along an axis (the hash's cell keys are exact below that).
    std::vector<char> marked;
    auto mark_about = [&](const cell& o) {
      cell a = o, e = o;
      for (std::size_t k = 0; k < D; ++k) a[k] = std::clamp(o[k] - 1, 0l, dims[k] - 1), e[k] = std::clamp(o[k] + 1, 0l, dims[k] - 1);
      if constexpr (D == 3) {
        for (long z = a[2]; z <= e[2]; ++z)
          for (long y = a[1]; y <= e[1]; ++y)
            std::fill_n(marked.begin() + ((z * dims[1] + y) * dims[0] + a[0]), e[0] - a[0] + 1, 1);
      } else {
        for (long y = a[1]; y <= e[1]; ++y) std::fill_n(marked.begin() + (y * dims[0] + a[0]), e[0] - a[0] + 1, 1);
      }
    };
    if (cells_total <= double(1 << 26)) {
      marked.assign(static_cast<std::size_t>(cells_total), 0);
      if (dense) {
        for (std::size_t i = 0; i + 1 < first.size(); ++i) {
          if (first[i] == first[i + 1]) continue;
          cell o;
          std::size_t r = i;
          for (std::size_t k = 0; k < D; ++k) o[k] = static_cast<long>(r % static_cast<std::size_t>(dims[k])), r /= static_cast<std::size_t>(dims[k]);
          mark_about(o);
        }
      } else {
        near.for_each_occupied(mark_about);
      }
    }
    auto clear_of_boundary = [&](const point<D>& q) {
      const auto c = near.cell_of(q);
      if (!marked.empty() && !marked[index_of(c)]) return true;
      if (!dense) return near.visit_ring(q, 1, [&](std::uint32_t f) { return face_distance2(f, q) >= keep * keep; });
      // the faces in the cells within one cell of q's (clamped) cell
      cell a, e;
      for (std::size_t k = 0; k < D; ++k) {
        const long x = std::clamp(c[k], 0l, dims[k] - 1);
        a[k] = std::max(x - 1, 0l), e[k] = std::min(x + 1, dims[k] - 1);
      }
      // a face meets several of those cells: each is measured once (the few seen so far are kept)
      std::array<std::uint32_t, 16> seen;
      std::size_t n_seen = 0;
      cell at = a;
      for (;;) {
        const std::size_t i = index_of(at);
        for (auto j = first[i]; j < first[i + 1]; ++j) {
          const std::uint32_t f = listed[j];
          if (std::find(seen.begin(), seen.begin() + static_cast<long>(n_seen), f) != seen.begin() + static_cast<long>(n_seen)) continue;
          if (face_distance2(f, q) < keep * keep) return false;
          if (n_seen < seen.size()) seen[n_seen++] = f;
        }
        std::size_t k = 0;
        while (k < D && ++at[k] > e[k]) at[k] = a[k], ++k;
        if (k == D) return true;
      }
    };
    // lattice: BCC in 3D (nearest-neighbour distance h), triangular in 2D; the origin is shifted
    // by odd fractions so lattice points rarely sit exactly on axis-aligned input planes
    const double a = D == 3 ? 2 * h / std::sqrt(3.0) : h;
    const double rowh = D == 3 ? a : h * std::sqrt(3.0) / 2;
    std::array<long, D> n;
    for (std::size_t k = 0; k < D; ++k) n[k] = static_cast<long>((hi[k] - lo[k]) / (k == 1 && D == 2 ? rowh : a)) + 2;
    // the lattice point k of slab s (its last index): 3D k = 2 (i n1 + j) + corner/centre
    const long slabs = n[D - 1];
    const std::size_t per_slab = D == 3 ? static_cast<std::size_t>(2 * n[0] * n[1]) : static_cast<std::size_t>(n[0]);
    auto lattice_point = [&](long s, std::size_t k) -> point<D> {
      if constexpr (D == 3) {
        const auto ij = static_cast<long>(k / 2);
        const long i = ij / n[1], j = ij % n[1];
        point3 q{lo[0] + a * (static_cast<double>(i) + 0.0137), lo[1] + a * (static_cast<double>(j) + 0.0271),
                 lo[2] + a * (static_cast<double>(s) + 0.0419)};
        if (k % 2) q = q + point3{a / 2, a / 2, a / 2};
        return q;
      } else {
        const auto i = static_cast<long>(k);
        return point2{lo[0] + a * (static_cast<double>(i) + 0.0137 + 0.5 * static_cast<double>(s % 2)),
                      lo[1] + rowh * (static_cast<double>(s) + 0.0271)};
      }
    };
    // 1. which points are clear of the boundary, in parallel by eighths of slabs (slabs near many
    // faces cost more; whole slabs, handed out in order, left one thread the last costly one)
    std::vector<std::vector<char>> clear(static_cast<std::size_t>(slabs));
    for (auto& c : clear) c.resize(per_slab);
    std::vector<long> ids(static_cast<std::size_t>(slabs));
    std::iota(ids.begin(), ids.end(), 0l);
    constexpr long parts = 8;
    std::vector<long> pieces(static_cast<std::size_t>(slabs * parts));
    std::iota(pieces.begin(), pieces.end(), 0l);
    for_each(execution::par(co.threads), pieces, [&](long x) {
      const long s = x / parts, part = x % parts;
      auto& c = clear[static_cast<std::size_t>(s)];
      const std::size_t from = per_slab * static_cast<std::size_t>(part) / parts, to = per_slab * static_cast<std::size_t>(part + 1) / parts;
      for (std::size_t k = from; k < to; ++k) c[k] = clear_of_boundary(lattice_point(s, k)) ? 1 : 0;
    });
    // 2. whether they lie in a segment. Lattice neighbours (3D: a corner and the 8 centres about
    // it; 2D: the 6 about a point) are h apart, so no face passes between two clear neighbours
    // (it would come within h/2 < keep of one): the points joined through clear neighbours lie on
    // one side of every face, and the exact point location is asked once per such set, at its
    // first point. Skipped (each point asked) for a lattice of over 2^24 points, or coordinates
    // so far from the origin, against h, that rounding nears the margin.
    double mag = 0;
    for (std::size_t k = 0; k < D; ++k) mag = std::max({mag, std::abs(lo[k]), std::abs(hi[k]) + 2 * a});
    const double points_total = static_cast<double>(per_slab) * static_cast<double>(slabs);
    const bool joined = points_total <= double(1 << 24) && mag * 256 * std::numeric_limits<double>::epsilon() < 1e-9 * h;
    std::vector<char> in_of;             // per root: in a segment
    std::vector<std::uint32_t> root_of;  // per point: its root
    if (joined) {
      const std::size_t total = per_slab * static_cast<std::size_t>(slabs);
      auto is_clear = [&](std::size_t x) { return clear[x / per_slab][x % per_slab] != 0; };
      union_find<std::uint32_t> uf(total);
      auto link = [&](std::size_t x, std::size_t y) {
        if (is_clear(y)) uf.unite(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
      };
      for (long s = 0; s < slabs; ++s)
        for (std::size_t k = 0; k < per_slab; ++k) {
          const std::size_t x = static_cast<std::size_t>(s) * per_slab + k;
          if (!is_clear(x)) continue;
          if constexpr (D == 3) {
            if (k % 2) continue;  // from the corners only: each to the centres of the 8 cubes about it
            const auto ij = static_cast<long>(k / 2);
            const long i = ij / n[1], j = ij % n[1];
            for (long ds = -1; ds <= 0; ++ds)
              for (long di = -1; di <= 0; ++di)
                for (long dj = -1; dj <= 0; ++dj) {
                  const long S = s + ds, I = i + di, J = j + dj;
                  if (S < 0 || I < 0 || J < 0) continue;
                  link(x, static_cast<std::size_t>(S) * per_slab + static_cast<std::size_t>(2 * (I * n[1] + J) + 1));
                }
          } else {
            const auto i = static_cast<long>(k);
            if (i + 1 < n[0]) link(x, x + 1);
            if (s + 1 < slabs) {
              const long other = s % 2 ? i + 1 : i - 1;  // the row above is shifted by half the other way
              for (long I : {i, other})
                if (I >= 0 && I < n[0]) link(x, static_cast<std::size_t>(s + 1) * per_slab + static_cast<std::size_t>(I));
            }
          }
        }
      // every point to its root (the smallest index of its set: its first point; parents have
      // smaller indices, so one pass in order), the roots asked in parallel
      auto& up = uf.up;
      for (std::size_t x = 0; x < total; ++x) up[x] = up[up[x]];
      std::vector<std::uint32_t> roots;
      for (std::size_t x = 0; x < total; ++x)
        if (up[x] == x && is_clear(x)) roots.push_back(static_cast<std::uint32_t>(x));
      std::vector<char> root_in(roots.size());
      std::vector<std::size_t> which(roots.size());
      std::iota(which.begin(), which.end(), std::size_t{0});
      for_each(execution::par(co.threads), which, [&](std::size_t r) {
        const std::uint32_t x = roots[r];
        root_in[r] = m.at.in_segment(lattice_point(static_cast<long>(x / per_slab), x % per_slab)) ? 1 : 0;
      });
      in_of.assign(total, 0);
      for (std::size_t r = 0; r < roots.size(); ++r) in_of[roots[r]] = root_in[r];
      root_of = std::move(up);
    }
    // 3. the points kept, in slab order
    std::vector<std::vector<point<D>>> kept(static_cast<std::size_t>(slabs));
    for_each(execution::par(co.threads), ids, [&](long s) {
      // filled locally, moved once: neighbouring vectors' headers share cache lines
      std::vector<point<D>> out_s;
      std::uint32_t hint = location::locator<D>::no_cell;
      const auto& c = clear[static_cast<std::size_t>(s)];
      for (std::size_t k = 0; k < per_slab; ++k) {
        if (!c[k]) continue;
        const point<D> q = lattice_point(s, k);
        if (joined ? in_of[root_of[static_cast<std::size_t>(s) * per_slab + k]] != 0 : in_segment(q, hint)) out_s.push_back(q);
      }
      kept[static_cast<std::size_t>(s)] = std::move(out_s);
    });
    for (const auto& k : kept) out.insert(out.end(), k.begin(), k.end());
  }
  add_cloud(out, cloud, m, dropped, threads);
  return out;
}

}  // namespace

template <std::size_t D>
std::vector<point<D>> size_points<D>::operator()(const plc<D>& p, double h, const std::vector<point<D>>& cloud,
                                                 std::size_t& dropped, const conformer::options& co,
                                                 bool lattice) const {
  dropped = 0;
  if ((h <= 0 || !lattice) && cloud.empty()) return {};
  const coarse_model<D> m(p, co);
  return lattice_points(m, h, cloud, dropped, co.threads, lattice);
}

template <std::size_t D>
std::vector<point<D>> size_points<D>::operator()(const plc<D>& p, const sizing::size_field<D>& h,
                                                 const std::vector<point<D>>& cloud, std::size_t& dropped,
                                                 const conformer::options& co) const {
  dropped = 0;
  const coarse_model<D> m(p, co);
  if (h.uniform()) return lattice_points(m, h.global(), cloud, dropped, co.threads, std::isfinite(h.global()));
  return field_points(m, h, cloud, dropped, co.threads);
}

template <std::size_t D>
domain<D> assemble_pieces(const std::vector<point<D>>& pts, const conformer::labelling& l, const pieces_t<D>& cells,
                          unsigned threads);

template <std::size_t D>
domain<D> mesh_segments<D>::operator()(const conformer::boundary<D>& b, const conformer::labelling& l,
                                       unsigned threads) const {
  std::vector<point<D>> extended;
  front::creation_stats st;
  const auto cells = create ? wrap_all_creating(extended, b, l, threads, *create, st) : wrap_pieces(b.points, b, l, threads);
  if (create && created) *created = st;
  return assemble_pieces(create ? extended : b.points, l, cells, threads);
}

template <std::size_t D>
std::vector<std::vector<cell_t<D>>> mesh_segments<D>::wrap(const conformer::boundary<D>& b, const conformer::labelling& l,
                                                           unsigned threads) {
  auto pieces = wrap_pieces(b.points, b, l, threads);
  std::vector<std::vector<cell_t<D>>> out(pieces.size());
  for (std::size_t r = 0; r < pieces.size(); ++r) {
    std::size_t n = 0;
    for (const auto& pc : pieces[r]) n += pc.size();
    out[r].reserve(n);
    for (const auto& pc : pieces[r]) out[r].insert(out[r].end(), pc.begin(), pc.end());
  }
  return out;
}

template <std::size_t D>
domain<D> mesh_segments<D>::assemble(const std::vector<point<D>>& pts, const conformer::labelling& l,
                                     std::vector<std::vector<cell_t<D>>> cells, unsigned threads) {
  pieces_t<D> pieces(cells.size());
  for (std::size_t r = 0; r < cells.size(); ++r) pieces[r].push_back(std::move(cells[r]));
  return assemble_pieces(pts, l, pieces, threads);
}

/// The domain of the cells (region -> pieces) on points `pts`: segments in number order, the
/// points used in their order.
template <std::size_t D>
domain<D> assemble_pieces(const std::vector<point<D>>& pts, const conformer::labelling& l, const pieces_t<D>& cells,
                          unsigned threads) {
  // every piece of every region is a task: mark the points used, then copy the cells renumbered
  struct task {
    std::size_t region, piece, offset;  // offset: of the piece's cells in its segment
  };
  std::vector<task> tasks;
  std::vector<std::size_t> total(cells.size(), 0);
  for (std::size_t r = 0; r < cells.size(); ++r)
    for (std::size_t k = 0; k < cells[r].size(); ++k) {
      tasks.push_back({r, k, total[r]});
      total[r] += cells[r][k].size();
    }
  auto cost = [&](const task& t) { return static_cast<double>(cells[t.region][t.piece].size()); };
  std::vector<vertex_id> remap(pts.size(), no_vertex);
  for_each(execution::par(threads), tasks, [&](const task& t) {
    // every writer stores the same value: relaxed atomic stores keep that race-free
    for (const auto& c : cells[t.region][t.piece])
      for (auto v : c) std::atomic_ref<vertex_id>(remap[v]).store(0, std::memory_order_relaxed);
  }, cost);
  // compact the points actually used, keeping their order
  domain<D> d;
  vertex_id next = 0;
  for (vertex_id v = 0; v < pts.size(); ++v)
    if (remap[v] == 0) remap[v] = next++;
  d.mutable_points().reserve(next);
  for (vertex_id v = 0; v < pts.size(); ++v)
    if (remap[v] != no_vertex) d.mutable_points().push_back(pts[v]);
  std::vector<std::size_t> order(l.regions.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto x, auto y) { return l.regions[x].number < l.regions[y].number; });
  std::vector<std::vector<cell_t<D>>*> out(cells.size());
  for (std::size_t r : order) {
    auto& s = d.add_segment(l.regions[r].name, l.regions[r].number);
    out[r] = &s.mutable_cells();
    out[r]->resize(total[r]);
  }
  for_each(execution::par(threads), tasks, [&](const task& t) {
    auto* to = out[t.region]->data() + t.offset;
    for (auto c : cells[t.region][t.piece]) {
      for (auto& v : c) v = remap[v];
      *to++ = c;
    }
  }, cost);
  d.sync_slots();
  // segments side by side, largest first; a large one also splits its own passes across threads
  // that come free (nested loops), so the small segments no longer wait in line behind it. Each
  // segment's error is kept and the first in segment order thrown: the same for any thread count.
  auto& segs = d.segments();
  std::vector<std::size_t> ids(segs.size());
  std::iota(ids.begin(), ids.end(), std::size_t{0});
  std::vector<std::exception_ptr> failed(segs.size());
  for_each(execution::par(threads), ids, [&](std::size_t k) {
    try {
      segs[k].finalize(threads);
    } catch (...) {
      failed[k] = std::current_exception();
    }
  }, [&](std::size_t k) { return static_cast<double>(segs[k].num_cells()); });
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
  return d;
}

namespace {
/// The sizing spec the options give for dimension D (sizing2 or sizing3).
template <std::size_t D>
const sizing::spec<D>& sizing_spec(const options& o) {
  if constexpr (D == 2)
    return o.sizing2;
  else
    return o.sizing3;
}
}  // namespace

template <std::size_t D>
domain<D> mesh(const plc<D>& p, const std::vector<point<D>>& cloud, const options& o, report& r) {
  using clock = std::chrono::steady_clock;
  auto t = clock::now();
  auto lap = [&](const char* stage) {
    const auto now = clock::now();
    r.times.push_back({stage, std::chrono::duration<double>(now - t).count()});
    t = now;
    if (o.progress) o.progress(std::string(stage) + " done");
  };
  // a self-intersecting PLC has no conforming mesh: the conformer would refine it forever
  plc_check::require_no_self_intersections(p);
  lap("check");
  conformer::options co = o.conform;
  co.size = o.size;
  co.threads = o.threads;
  const bool creating = o.interior == fill::rules && o.size > 0;
  // 2D with --quality: the refinement places the interior points (circumcentres of triangles too
  // large for the size field, as Triangle does), not a lattice: a point inserted into an
  // equilateral lattice leaves 30-30-120 triangles, and above 30 degrees each fix made the next
  // (the benchmark structures did not converge at 31-34 degrees with the lattice)
  const bool refined_interior = D == 2 && o.quality && !creating;
  std::vector<point<D>> volume;
  sizing::size_field<D> field;
  bool feature_size_fits = false;  // the local feature size was built within its budget
  // a region's maximum volume (TetGen's region attribute) is a size constraint of its own
  const bool volumes = std::any_of(p.regions.begin(), p.regions.end(), [](const auto& x) { return x.max_volume > 0; });
  if ((o.graded || volumes) && !creating) {
    // the size field from the unsized conformed boundary, then the points it asks for
    const coarse_model<D> m(p, co);
    sizing::spec<D> sp = sizing_spec<D>(o);
    sp.global = o.size;
    sizing::add_region_volumes(sp, p);
    std::vector<std::array<int, 2>> sides(m.b.faces.size(), {0, 0});
    for (std::size_t f = 0; f < sides.size() && f < m.l.side.size(); ++f)
      for (std::size_t k = 0; k < 2; ++k)
        if (const int ri = m.l.side[f][k]; ri >= 0) sides[f][k] = m.l.regions[static_cast<std::size_t>(ri)].number;
    sizing::boundary_view<D> view{m.b.points, m.b.plc_points, m.b.faces, m.b.face_source, sides, p.source};
    std::function<void(std::size_t, std::size_t)> tick;
    if (o.progress)
      tick = [&o](std::size_t done, std::size_t all) {
        o.progress("sizing: local feature size, " + std::to_string(done) + " of " + std::to_string(all) + " boundary faces");
      };
    field = sizing::build(view, sp, o.threads, tick);
    feature_size_fits = sp.feature_size;
    if (o.progress) o.progress("sizing: placing points");
    r.uniform_size = field.uniform();
    r.min_size = field.minimum();
    r.size_sources = field.sources();
    if (field.uniform()) {
      volume = lattice_points(m, o.size, cloud, r.dropped_points, o.threads, o.size > 0 && !refined_interior);
    } else {
      volume = refined_interior ? lattice_points(m, 0, cloud, r.dropped_points, o.threads, false)
                                : field_points(m, field, cloud, r.dropped_points, o.threads);
      if constexpr (D == 2)
        co.local_size2 = [&field](const point2& x) { return field(x); };
      else
        co.local_size3 = [&field](const point3& x) { return field(x); };
    }
  } else {
    volume = size_points<D>{}(p, o.size, cloud, r.dropped_points, co, !creating && !refined_interior);
    r.min_size = o.size;
  }
  r.volume_points = volume.size();
  lap("sizing");
  if (o.progress) o.progress("conforming the boundary (" + std::to_string(volume.size()) + " volume points)");
  auto b = conform<D>{}(p, volume, co);
  r.steiner = b.steiner;
  lap("conform");
  auto l = conformer::label(b, p, o.threads);
  lap("label");
  if (o.progress)
    o.progress("meshing " + std::to_string(l.regions.size()) + " segments (" + std::to_string(b.points.size()) + " points)");
  rules::rule_set defaults;
  front::creation_options fo;
  if (creating) {
    if (!o.front_rules) defaults = rules::default_rules(D == 3 ? "front3d" : "front2d");
    fo.rules = o.front_rules ? o.front_rules : &defaults.front;
    fo.h = o.size;
    fo.too_far = o.too_far;
  }
  domain<D> d;
  if (!o.quality) {
    d = mesh_segments<D>{creating ? &fo : nullptr, &r.creation}(b, l, o.threads);
  } else {
    // Delaunay refinement (modules/refinement): rounds of circumcentres and boundary splits, the
    // boundary resumed and only the cavities of the new points meshed again each round
    if (creating)
      throw std::invalid_argument("--quality does not combine with --fill rules: the refinement places the interior points itself");
    auto cells = mesh_segments<D>::wrap(b, l, o.threads);
    lap("mesh");
    refinement::options ro;
    ro.bound = o.quality_bound;
    ro.sliver_angle = o.sliver_angle;
    ro.acute_guard = o.acute_guard;
    ro.max_rounds = o.quality_rounds;
    ro.threads = o.threads;
    ro.progress = o.progress;
    if (!feature_size_fits)
      // the bad elements growing round after round: can the input's features be met at all? The
      // local feature size within its budget says so (a layer 5e-6 thick in a unit model needs
      // some 1e10 pieces, and the refinement as many points: it ran on for hours, each round
      // slower). Asked once, from the boundary as it is then; the field itself is dropped
      ro.on_growth = [&](std::size_t bad, std::size_t rounds) {
        if (o.progress) o.progress("quality: the bad elements keep growing; checking the input's feature sizes");
        sizing::spec<D> features;  // the local feature size alone, with the budget asked for
        features.max_pieces = sizing_spec<D>(o).max_pieces;
        try {
          sizing::build<D>({b.points, b.plc_points, b.faces, b.face_source, {}, p.source}, features, o.threads);
        } catch (const sizing::too_fine& e) {
          throw std::runtime_error(p.source + ": --quality: the elements above the bound grew to " + std::to_string(bad) +
                                   " in " + std::to_string(rounds) + " rounds, and the input has features far below the model's size" +
                                   (e.closest.empty() ? "" : ", " + e.closest) + " (their local feature size alone needs more than " +
                                   std::to_string(features.max_pieces) +
                                   " boundary pieces): the bound cannot be met there; thicken or remove them, or mesh without --quality");
        }
      };
    if (refined_interior) {
      if constexpr (D == 2) {
        if (!field.uniform())
          ro.size2 = [&field](const point2& x) { return field(x); };
        else if (o.size > 0)
          ro.size2 = [h = o.size](const point2&) { return h; };
      }
    }
    refinement::meshers<D> m;
    m.wrap = [&](const conformer::boundary<D>& bb, const conformer::labelling& ll) { return mesh_segments<D>::wrap(bb, ll, o.threads); };
    m.assemble = [&](const conformer::boundary<D>& bb, const conformer::labelling& ll, refinement::cells_by_region<D> cc) {
      return mesh_segments<D>::assemble(bb.points, ll, std::move(cc), o.threads);
    };
    d = refinement::refine(p, b, l, std::move(cells), co, ro, m, r.refinement);
    r.quality = true;
    r.steiner = b.steiner;
  }
  // the input's markers on the faces that lie on marked facets (every boundary face is a mesh
  // face: the mesh conforms), for the writers
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const std::size_t src = b.face_source[f];
    int marker = 0;
    if constexpr (D == 3)
      marker = src < p.facets.size() ? p.facets[src].marker : 0;
    else
      marker = src < p.edge_markers.size() ? p.edge_markers[src] : 0;
    if (marker != 0) d.marked_faces().push_back({b.faces[f], marker});
  }
  d.marker_names() = p.marker_names;
  lap(o.quality ? "quality" : "mesh");
  if (o.verify) {
    // against the input PLC itself, not the conformed boundary and labels the mesh was made from
    verify::options vo;
    vo.threads = o.threads;
    vo.facet_tolerance = o.verify_tolerance;
    r.problems = verify::check(d, p, vo).problems;
    lap("verify");
  }
  return d;
}

template <std::size_t D>
quality measure(const domain<D>& d, unsigned threads) {
  const auto& p = d.points();
  const double rad = 180 / std::numbers::pi;
  // the cells in pieces, measured in parallel, each piece its own tallies (merged in order: the
  // sums, minima, maxima and the median do not depend on it)
  using cell = typename std::decay_t<decltype(d.segments()[0].cell_data())>::value_type;
  constexpr std::size_t piece_size = 1 << 13;
  std::vector<std::span<const cell>> pieces;
  for (const auto& s : d.segments()) {
    const auto cs = s.cell_data();
    for (std::size_t a = 0; a < cs.size(); a += piece_size) pieces.push_back(cs.subspan(a, std::min(piece_size, cs.size() - a)));
  }
  std::vector<quality> part(pieces.size());
  std::vector<std::vector<double>> part_ratios(pieces.size());
  std::vector<std::size_t> ids(pieces.size());
  std::iota(ids.begin(), ids.end(), std::size_t{0});
  for_each(execution::par(threads), ids, [&](std::size_t k) {
    quality& q = part[k];
    q.min_angle = 180;
    q.shortest_edge = std::numeric_limits<double>::infinity();
    auto& ratios = part_ratios[k];
    ratios.reserve(pieces[k].size());
    for (const auto& c : pieces[k]) {
      double shortest = 1e300;
      for (std::size_t i = 0; i <= D; ++i)
        for (std::size_t j = i + 1; j <= D; ++j) shortest = std::min(shortest, distance(p[c[i]], p[c[j]]));
      double r;
      // the element's angles by their cosines: the smallest angle is the arccosine of the largest
      double most = -1, least = 1;
      if constexpr (D == 2) {
        const double a = distance(p[c[1]], p[c[2]]), b = distance(p[c[0]], p[c[2]]), e = distance(p[c[0]], p[c[1]]);
        const point2 u = p[c[1]] - p[c[0]], v = p[c[2]] - p[c[0]];
        const double area = 0.5 * std::abs(u[0] * v[1] - u[1] * v[0]);
        r = a * b * e / (4 * area);
        for (std::size_t i = 0; i < 3; ++i) {
          const point2 x = p[c[(i + 1) % 3]] - p[c[i]], y = p[c[(i + 2) % 3]] - p[c[i]];
          const double cosv = std::clamp(dot(x, y) / std::sqrt(dot(x, x) * dot(y, y)), -1.0, 1.0);
          most = std::max(most, cosv), least = std::min(least, cosv);
        }
      } else {
        const point3 u = p[c[1]] - p[c[0]], v = p[c[2]] - p[c[0]], w = p[c[3]] - p[c[0]];
        double det;
        const point3 cc = geometry::tetrahedron_circumcentre_offset(u, v, w, det);
        r = std::sqrt(dot(cc, cc));
        std::tie(most, least) = geometry::dihedral_cosines(p, c);
      }
      q.shortest_edge = std::min(q.shortest_edge, shortest);
      const double lo = std::min(180.0, std::acos(most) * rad), hi = std::max(0.0, std::acos(least) * rad);
      q.min_angle = std::min(q.min_angle, lo), q.max_angle = std::max(q.max_angle, hi);
      q.below5 += lo < 5, q.below10 += lo < 10, q.above170 += hi > 170;
      ++q.angle_histogram[std::min<std::size_t>(6, static_cast<std::size_t>(std::max(0.0, lo) / 10))];
      const double ratio = r / shortest;
      std::size_t bin = 0;
      while (bin < quality::ratio_bounds.size() && !(ratio < quality::ratio_bounds[bin])) ++bin;
      ++q.ratio_histogram[bin];
      ratios.push_back(ratio);
    }
  }, [&](std::size_t k) { return static_cast<double>(pieces[k].size()); });
  quality q;
  q.min_angle = 180;
  q.shortest_edge = std::numeric_limits<double>::infinity();
  std::vector<double> ratios;
  for (std::size_t k = 0; k < part.size(); ++k) {
    const quality& x = part[k];
    q.min_angle = std::min(q.min_angle, x.min_angle), q.max_angle = std::max(q.max_angle, x.max_angle);
    q.shortest_edge = std::min(q.shortest_edge, x.shortest_edge);
    q.below5 += x.below5, q.below10 += x.below10, q.above170 += x.above170;
    for (std::size_t i = 0; i < q.angle_histogram.size(); ++i) q.angle_histogram[i] += x.angle_histogram[i];
    for (std::size_t i = 0; i < q.ratio_histogram.size(); ++i) q.ratio_histogram[i] += x.ratio_histogram[i];
    ratios.insert(ratios.end(), part_ratios[k].begin(), part_ratios[k].end());
  }
  q.elements = ratios.size();
  if (ratios.empty()) q.shortest_edge = 0;
  if (!ratios.empty()) {
    // the median as a full sort would place it; the extremes
    const auto [lo, hi] = std::minmax_element(ratios.begin(), ratios.end());
    q.min_ratio = *lo, q.max_ratio = *hi;
    std::nth_element(ratios.begin(), ratios.begin() + static_cast<long>(ratios.size() / 2), ratios.end());
    q.median_ratio = ratios[ratios.size() / 2];
  }
  return q;
}

template quality measure<2>(const domain<2>&, unsigned);
template quality measure<3>(const domain<3>&, unsigned);
template struct size_points<2>;
template struct size_points<3>;
template struct mesh_segments<2>;
template struct mesh_segments<3>;
template domain<2> mesh<2>(const plc<2>&, const std::vector<point2>&, const options&, report&);
template domain<3> mesh<3>(const plc<3>&, const std::vector<point3>&, const options&, report&);

}  // namespace gsse::pipeline
