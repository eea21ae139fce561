#include "gsse/pipeline/pipeline.hpp"
#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/dihedral.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
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

#include "gsse/front/front_mesher.hpp"
#include "gsse/front/gift_wrap.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/location/locator.hpp"
#include "gsse/placement/placement.hpp"
#include "gsse/plc/intersections.hpp"
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
  const front::boundary_faces<D> faces(std::span<const point<D>>(b.points), std::span<const std::array<vertex_id, D>>(b.faces),
                                       std::span<const vertex_id>(b.face_apex));
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

/// The coarse model's boundary as the placement reads it.
template <std::size_t D>
placement::surface<D> surface_of(const coarse_model<D>& m) {
  return {m.b.points, m.b.faces};
}

/// Lattice points about h apart (see size_points; none unless `lattice`) plus the cloud.
template <std::size_t D>
std::vector<point<D>> lattice_points(const coarse_model<D>& m, double h, const std::vector<point<D>>& cloud,
                                     std::size_t& dropped, unsigned threads, bool lattice) {
  auto out = lattice ? placement::lattice_points<D>(surface_of(m), m.at, h, threads) : std::vector<point<D>>{};
  placement::add_cloud<D>(out, cloud, m.at, dropped, threads);
  return out;
}

/// Points of the size field `h` (graded placement, modules/sizing) plus the cloud.
template <std::size_t D>
std::vector<point<D>> field_points(const coarse_model<D>& m, const sizing::size_field<D>& h,
                                   const std::vector<point<D>>& cloud, std::size_t& dropped, unsigned threads,
                                   std::vector<double>* lower = nullptr) {
  std::vector<int> numbers;
  for (const auto& r : m.l.regions) numbers.push_back(r.number);
  auto out = placement::field_points<D>(surface_of(m), m.at, numbers, h, threads, lower);
  placement::add_cloud<D>(out, cloud, m.at, dropped, threads, lower);
  return out;
}

/// The coarse model's boundary and labels, where a caller keeps them past the placement.
template <std::size_t D>
using labelled_boundary = std::pair<conformer::boundary<D>, conformer::labelling>;

/// size_points' uniform case; the coarse model's boundary and labels, if one was built, are
/// handed to `kept` (mesh() labels the sized boundary from them).
template <std::size_t D>
std::vector<point<D>> uniform_points(const plc<D>& p, double h, const std::vector<point<D>>& cloud, std::size_t& dropped,
                                     const conformer::options& co, bool lattice,
                                     std::optional<labelled_boundary<D>>* kept = nullptr) {
  dropped = 0;
  if ((h <= 0 || !lattice) && cloud.empty()) return {};
  coarse_model<D> m(p, co);
  auto out = lattice_points(m, h, cloud, dropped, co.threads, lattice);
  if (kept) kept->emplace(std::move(m.b), std::move(m.l));
  return out;
}

}  // namespace

template <std::size_t D>
std::vector<point<D>> size_points<D>::operator()(const plc<D>& p, double h, const std::vector<point<D>>& cloud,
                                                 std::size_t& dropped, const conformer::options& co,
                                                 bool lattice) const {
  return uniform_points(p, h, cloud, dropped, co, lattice);
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
  // 3D, a size without --quality: the refinement's rounds for size alone (options::size_rounds);
  // decided once the field is known (a uniform --size, or a graded field)
  bool size_alone = false;
  std::vector<point<D>> volume;
  std::vector<double> volume_lower;  // graded: a lower bound of h at each volume point (the placement's)
  sizing::size_field<D> field;
  bool field_built = false;  // the field above was built (graded sizing or region volumes)
  bool feature_size_fits = false;  // the local feature size was built within its budget
  // a region's maximum volume (TetGen's region attribute) is a size constraint of its own
  const bool volumes = std::any_of(p.regions.begin(), p.regions.end(), [](const auto& x) { return x.max_volume > 0; });
  // the coarse model's boundary and labels, kept (its mesh and locator are not) where one was
  // built: the sized boundary is labelled from them (label_refined: the same PLC's facets, each
  // with the sides it had), and the conformer reads the facets' meshed sides from them
  std::optional<labelled_boundary<D>> coarse;
  if ((o.graded || volumes) && !creating) {
    // the size field from the unsized conformed boundary, then the points it asks for
    coarse_model<D> m(p, co);
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
    field_built = true;
    feature_size_fits = sp.feature_size;
    if (o.progress) o.progress("sizing: placing points");
    r.uniform_size = field.uniform();
    r.min_size = field.minimum();
    r.size_sources = field.sources();
    size_alone = !o.quality && o.size_rounds && (!field.uniform() || o.size > 0);
    if (field.uniform()) {
      volume = lattice_points(m, o.size, cloud, r.dropped_points, o.threads, o.size > 0 && !refined_interior);
    } else {
      volume = refined_interior ? lattice_points(m, 0, cloud, r.dropped_points, o.threads, false)
                                : field_points(m, field, cloud, r.dropped_points, o.threads,
                                               D == 3 && (o.quality || size_alone) ? &volume_lower : nullptr);
      if constexpr (D == 2)
        co.local_size2 = [&field](const point2& x, double cap) { return field.capped(x, cap); };
      else
        co.local_size3 = [&field](const point3& x, double cap) { return field.capped(x, cap); };
      if (std::isfinite(field.slope())) co.local_slope = field.slope();
    }
    coarse.emplace(std::move(m.b), std::move(m.l));
  } else {
    volume = uniform_points<D>(p, o.size, cloud, r.dropped_points, co, !creating && !refined_interior, &coarse);
    r.min_size = o.size;
    size_alone = !o.quality && o.size_rounds && !creating && o.size > 0;
  }
  const bool refining = o.quality || size_alone;
  r.volume_points = volume.size();
  lap("sizing");
  if (o.progress) o.progress("conforming the boundary (" + std::to_string(volume.size()) + " volume points)");
  // with --quality the conformer's state is kept for the refinement's first round (a session:
  // the same boundary as the conform stage, without a rebuild in the first round)
  std::optional<conformer::session<D>> session;
  // (not for the size rounds: they are one or two, often none, and the kept state is the size of
  // the boundary, held through the first mesh; their first round, if any, resumes instead)
  if constexpr (D == 3)
    if (coarse) co.sides_from = &coarse->first, co.sides_labels = &coarse->second;
  // boundary and interface faces that are Delaunay but not Gabriel are kept; the refinement's
  // rounds and the front's point creation (fill::rules) test each kept face's sphere
  // (conformer::face_encroached, front::boundary_faces; docs/design-decisions.md, "Boundary faces
  // need to be Delaunay, not Gabriel")
  co.delaunay_faces = D == 3 && !o.gabriel;
  r.delaunay_faces = co.delaunay_faces;
  // 3D with --quality and a uniform size: a thin layer's walls are seeded at its gap's scale, where
  // its prisms meet the bound, instead of the rounds refining them (conformer::options::thin_layer)
  if (D == 3 && o.quality && o.size > 0 && !field_built && co.thin_layer == 0)
    co.thin_layer = conformer::thin_layer_ratio(refinement::ratio_bound(3, o.quality_bound));
  auto b = o.quality ? session.emplace(p, co).start(volume) : conform<D>{}(p, volume, co);
  r.steiner = b.steiner;
  lap("conform");
  auto l = coarse ? conformer::label_refined(b, p, coarse->first, coarse->second, o.threads) : conformer::label(b, p, o.threads);
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
  if (!refining) {
    d = mesh_segments<D>{creating ? &fo : nullptr, &r.creation}(b, l, o.threads);
  } else {
    // Delaunay refinement (modules/refinement): rounds of circumcentres and boundary splits, the
    // boundary resumed and only the cavities of the new points meshed again each round
    if (creating)
      throw std::invalid_argument("--quality does not combine with --fill rules: the refinement places the interior points itself");
    auto cells = mesh_segments<D>::wrap(b, l, o.threads);
    lap("mesh");
    refinement::options ro;
    // size alone: no shape bound and no sliver rule, only the size rule below
    ro.bound = size_alone ? std::numeric_limits<double>::infinity() : o.quality_bound;
    ro.sliver_angle = size_alone ? 0.0 : o.sliver_angle;
    ro.fill = o.cavity_fill;
    ro.acute_guard = o.acute_guard;
    ro.max_rounds = o.quality_rounds;
    ro.threads = o.threads;
    ro.progress = o.progress;
    // the boundary before the rounds, for the check below: the rounds' splits change no feature,
    // and scad_example009's check of the boundary after 10 rounds took about 3 s longer
    struct {
      std::vector<point<D>> points;
      std::vector<std::array<vertex_id, D>> faces;
      std::vector<std::uint32_t> face_source;
    } before;
    if (!feature_size_fits) {
      before.points.assign(b.points.begin(), b.points.end());
      before.faces.assign(b.faces.begin(), b.faces.end());
      before.face_source.assign(b.face_source.begin(), b.face_source.end());
      // the bad elements growing round after round: can the input's features be met at all? The
      // local feature size within its budget says so (a layer 5e-6 thick in a unit model needs
      // some 1e10 pieces, and the refinement as many points: it ran on for hours, each round
      // slower). Asked once, of the boundary as it was before the rounds; the pieces are
      // counted, not kept (sizing::check_feature_size)
      ro.on_growth = [&](std::size_t bad, std::size_t rounds) {
        if (o.progress) o.progress("quality: the bad elements keep growing; checking the input's feature sizes");
        const std::size_t budget = sizing_spec<D>(o).max_pieces;
        try {
          sizing::check_feature_size<D>({before.points, b.plc_points, before.faces, before.face_source, {}, p.source}, budget, o.threads);
        } catch (const sizing::too_fine& e) {
          throw std::runtime_error(p.source + (size_alone ? ": the size rounds: the elements too large grew to " : ": --quality: the elements above the bound grew to ") + std::to_string(bad) +
                                   " in " + std::to_string(rounds) + " rounds, and the input has features far below the model's size" +
                                   (e.closest.empty() ? "" : ", " + e.closest) + " (their local feature size alone needs more than " +
                                   std::to_string(budget) +
                                   (size_alone ? " boundary pieces): the size cannot be met there; thicken or remove them, or give a larger size"
                                               : " boundary pieces): the bound cannot be met there; thicken or remove them, or mesh without --quality"));
        }
      };
    }
    if (refined_interior || size_alone) {
      if constexpr (D == 2) {
        if (!field.uniform()) {
          ro.size2 = [&field](const point2& x) { return field(x); };
          ro.segment_maximum2 = [&field](int number) { return field.segment_maximum(number); };
        }
        else if (o.size > 0)
          ro.size2 = [h = o.size](const point2&) { return h; };
      }
    }
    // 3D, a uniform size: no edge longer than 1.5 H (the band between the boundary and the first
    // lattice layer, kept h/2 off every face, left 0.1-1.8% of the edges above it on the benchmark
    // structures; docs/benchmarks.md, thirty-fifth part)
    if constexpr (D == 3) {
      if (o.size > 0 && (!field_built || field.uniform())) ro.size3 = [h = o.size](const point3&) { return h; };
      // a graded field: the same 1.5 h, at each edge's midpoint (refinement::edge_sizes; graded
      // meshes had up to 0.5% of their edges above it, docs/benchmarks.md, forty-second part)
      if (field_built && !field.uniform()) {
        auto g = std::make_shared<refinement::edge_sizes>();
        g->h = [&field](const point3& x, double cap) { return field.capped(x, cap); };
        g->slope = field.slope();
        g->segment_maximum = [&field](int number) { return field.segment_maximum(number); };
        g->volume_lower = std::move(volume_lower);
        ro.graded3 = std::move(g);
      }
    }
    refinement::meshers<D> m;
    m.wrap = [&](const conformer::boundary<D>& bb, const conformer::labelling& ll) { return mesh_segments<D>::wrap(bb, ll, o.threads); };
    m.assemble = [&](const conformer::boundary<D>& bb, const conformer::labelling& ll, refinement::cells_by_region<D> cc) {
      return mesh_segments<D>::assemble(bb.points, ll, std::move(cc), o.threads);
    };
    d = refinement::refine(p, b, l, std::move(cells), co, ro, m, r.refinement, session ? &*session : nullptr);
    r.quality = o.quality;
    r.size_rounds = size_alone;
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
  lap(o.quality ? "quality" : size_alone ? "size" : "mesh");
  // the edges against the size they were made for: the field where there is one, else --size
  if (o.size_fit && (field_built || o.size > 0)) {
    r.size_fit = sizing::edge_fit<D>(d, field_built ? &field : nullptr, o.size, o.threads);
    r.size_measured = true;
    lap("size fit");
  }
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
