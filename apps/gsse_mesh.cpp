// gsse-mesh: PLC in, per-segment conforming Delaunay mesh out.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "allocator_tuning.hpp"
#include "gsse/io/node_ele.hpp"
#include "gsse/io/gmsh.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/io/sidecar.hpp"
#include "gsse/io/vtu.hpp"
#include "gsse/pipeline/pipeline.hpp"
#include "gsse/plc/region_points.hpp"
#include "gsse/rules/defaults.hpp"
#include "gsse/sizing/inputs.hpp"
#include "gsse/verify/verify.hpp"

namespace {

bool ends_with(const std::string& s, const char* e) {
  const std::size_t n = std::strlen(e);
  return s.size() >= n && s.compare(s.size() - n, std::string::npos, e) == 0;
}

void usage(std::FILE* to) {
  std::fputs(
      "usage: gsse-mesh INPUT [-o OUTPUT] [--size H] [--cloud POINTS.node] [--threads N] [--verify]\n"
      "                 [--quiet] [--stats FILE.json] [--max-steiner N] [--fill lattice|rules]\n"
      "                 [--rules FILE.rules] [--no-merge] [--gabriel] [--plc-out FILE.poly] [--msh 4.1|2.2] [--verify-tol R]\n"
      "                 [--grade G] [--no-feature-size] [--quality [B]] [--sliver-angle A] [--cavity-fill F]\n"
      "                 [--acute-guard F] [--quality-rounds N] [--size-fit] [--no-size-rounds]\n"
      "       gsse-mesh INPUT --check MESH [--threads N] [--quiet] [--verify-tol R]\n"
      "  INPUT    TetGen .poly/.smesh (3D), Triangle .poly (2D), or a closed surface: OFF, STL,\n"
      "           Gmsh .msh surface mesh (its volumes become segments)\n"
      "  -o       output mesh: .vtu, .msh, or .node (writes .node/.ele/.face beside it); boundary\n"
      "           and interface faces keep the input's facet markers (docs/io.md)\n"
      "  --msh    Gmsh format version of a .msh output: 4.1 (default) or 2.2 (ASCII, as devsim reads)\n"
      "  --size   target element size H (default: none, boundary conforming only); uniform unless\n"
      "           graded sizing is on (--grade, sidecar sizes, region volumes)\n"
      "  --grade  graded sizing (modules/sizing/README.md): neighbouring element sizes differ by at\n"
      "           most about the factor G (> 1, default 1.3); on by itself from the local feature\n"
      "           size, the .poly regions' maximum volumes and the sizing keys of INPUT's BASE.json\n"
      "           sidecar (per-segment sizes, refinement boxes, interface layers, background mesh)\n"
      "  --no-feature-size  leave the local feature size out of the size field\n"
      "  --quality [B]  Delaunay refinement (modules/refinement/README.md): 3D, no tetrahedron with a\n"
      "           radius-edge ratio above B (default 2.0, at least 1); 2D, no triangle with an angle\n"
      "           below B degrees (default 20.7, at most 33); the mesh stays conforming Delaunay.\n"
      "           3D with --size and B >= 1.4: a thin layer's walls are seeded at about 2 times\n"
      "           its thickness (2.2 at 1.414), where its prisms meet the bound\n"
      "  --sliver-angle A  with --quality in 3D: tetrahedra with a dihedral angle below A or above\n"
      "           180 - 2A degrees are refined too (default 5: none below 5 or above 170; 0: off)\n"
      "  --cavity-fill insertion|front  3D rounds (--quality, size rounds): how a round re-fills\n"
      "           the cells its points remove: by inserting them one at a time (default), or by the\n"
      "           front mesher; the same cells, in another order (for comparison)\n"
      "  --acute-guard F  with --quality: small input angles excepted (3D: bad elements whose\n"
      "           circumcentre lies within F times an acute vertex's protecting ball, or within F\n"
      "           times its length of a piece of an input edge with a dihedral angle below 60\n"
      "           degrees, or that encroach a boundary face whose circumcentre lies there; 2D: any\n"
      "           F > 0 turns on Shewchuk's rule); counted and located in the summary (default 1;\n"
      "           0: off). 3D also excepts, apart, bad elements whose circumradius is below 1/64\n"
      "           of the starting boundary's local spacing (the spacing floor: the rounds end)\n"
      "  --quality-rounds N  with --quality: stop after N rounds (default 250); the\n"
      "           elements left above the bound are reported\n"
      "  --cloud  extra interior points (.node); points outside every segment are dropped\n"
      "  --verify check the mesh against the input (valid, conforming, labelled, Delaunay); if it\n"
      "           fails: exit status 3, no output written (neither -o nor --stats)\n"
      "  --fill   interior points with --size: a lattice placed before meshing (default), or points\n"
      "           created by the front rules while meshing\n"
      "  --rules  rule set (see docs/rules.md), validated first: its split rules replace the conformer's,\n"
      "           its front rules the mesher's (front rules imply --fill rules)\n"
      "  --no-merge keep coplanar facets of one marker apart (by default they are merged across\n"
      "           edges no other facet uses, as TetGen does without -M)\n"
      "  --gabriel 3D: keep every boundary and interface face's equatorial ball empty (the faces\n"
      "           Gabriel; more points). By default faces whose ball holds points are kept when\n"
      "           they are Delaunay faces all the same\n"
      "  --size-fit measure every edge against the size at its midpoint (the size field, or --size)\n"
      "           and report how many lie within [0.5, 1.5] of it, below and above, in the summary\n"
      "           and --stats (quality.size_fit); a pass over every edge, seconds at 5e5 points\n"
      "  --no-size-rounds  with a size (--size, --grade) and without --quality: leave out the rounds\n"
      "           that refine every element with an edge above 1.5 h at its midpoint (on by default:\n"
      "           the placement alone left up to 25 edges of 1.3e5 above in 3D, 198 of 7.9e4 in 2D)\n"
      "  --verify-tol R  --verify with facet tolerance R (relative to the input's bounding-box\n"
      "           diagonal; default 1e-9; 0: face vertices exactly in their facets' planes, which\n"
      "           Steiner points on slanted facets cannot be)\n"
      "  --check  verify an existing mesh (.msh, or TetGen/Triangle .node/.ele with the segment\n"
      "           number as element attribute, any mesher's) against INPUT, as --verify does, and\n"
      "           exit: status 0 if it passes, 3 if not (the problems on stderr)\n"
      "  --plc-out write the input as read (with the region points placed in Gmsh volumes) as a\n"
      "           TetGen/Triangle .poly and exit without meshing (with no option but --threads,\n"
      "           --no-merge and --quiet)\n"
      "  environment: GSSE_MALLOC=system keeps glibc's malloc as it is (by default the run sets\n"
      "           GLIBC_TUNABLES for huge pages and starts again; not if GLIBC_TUNABLES or LD_PRELOAD\n"
      "           is set)\n",
      to);
}

struct args {
  std::string input, output, cloud, stats, rules, fill, plc_out, check;
  std::vector<std::string> meshing;  // the options given that concern meshing (--plc-out takes none)
  double size = 0, verify_tol = gsse::verify::options{}.facet_tolerance, grade = 0, quality_bound = 0;
  bool quality = false;
  double sliver_angle = gsse::refinement::options{}.sliver_angle;
  double acute_guard = gsse::refinement::options{}.acute_guard;
  std::size_t quality_rounds = 0;
  bool no_feature = false;
  unsigned threads = 1;
  bool verify = false, verify_tol_given = false, quiet = false, no_merge = false, msh22 = false;
  bool size_fit = false;  // --size-fit
  bool size_rounds = true;  // not --no-size-rounds
  bool gabriel = false;     // --gabriel
  gsse::refinement::cavity_fill cavity_fill = gsse::refinement::cavity_fill::insertion;  // --cavity-fill
  std::size_t max_steiner = gsse::conformer::options{}.max_steiner;
};

/// Refuses, before any work, a run that would write over one of its own inputs or write one file
/// twice. The traps: `-o m.node` beside m.poly writes the segment names to m.json, which is
/// m.poly's sidecar (its sizing keys and anything else in it would be lost); `--stats m.json`
/// beside m.poly is read back as the sidecar by the next run; `--stats g.json` with `-o g.node`
/// overwrites the mesh's own sidecar. Two existing paths are the same if they name one file
/// (symbolic and hard links too); others are compared after making them absolute and canonical.
/// The input's sidecar is refused as an output even where it does not exist yet: written, it
/// would be read back by the next run on the input (docs/io.md).
void refuse_overwrites(const args& a) {
  namespace fs = std::filesystem;
  auto same = [](const std::string& x, const std::string& y) {
    std::error_code e1, e2;
    if (fs::exists(x, e1) && fs::exists(y, e2)) return fs::equivalent(x, y, e1) && !e1;  // hard links too
    const fs::path px = fs::weakly_canonical(fs::absolute(x), e1), py = fs::weakly_canonical(fs::absolute(y), e2);
    return !e1 && !e2 ? px == py : fs::absolute(x).lexically_normal() == fs::absolute(y).lexically_normal();
  };
  std::vector<std::pair<std::string, std::string>> reads, writes;  // (path, what it is)
  const std::string sidecar = gsse::io::base_of(a.input) + ".json";
  reads.push_back({a.input, "the input"});
  reads.push_back({sidecar, "the input's sidecar (segment names and sizing are read from it, docs/io.md)"});
  if (!a.cloud.empty()) reads.push_back({a.cloud, "the --cloud file"});
  if (!a.rules.empty()) reads.push_back({a.rules, "the --rules file"});
  std::error_code ec;
  if (fs::is_regular_file(sidecar, ec)) {  // the background mesh it names (malformed: the error is the reader's, as later)
    const auto bg = gsse::io::read_sidecar(sidecar).sizing.background;
    if (!bg.empty()) {
      const fs::path rel(bg);
      const std::string at = rel.is_absolute() ? rel.string() : (fs::path(sidecar).parent_path() / rel).string();
      for (const auto& f : gsse::sizing::background_files(at)) reads.push_back({f, "the background mesh"});
    }
  }
  if (a.check.empty()) {
    const std::string& out = a.output;
    auto ends = [&](const char* e) { return ends_with(out, e); };
    if (ends(".vtu")) {
      writes.push_back({out, "-o " + out});
      writes.push_back({gsse::io::boundary_vtu_path(out), "-o " + out + "'s boundary companion"});
    } else if (ends(".msh")) {
      writes.push_back({out, "-o " + out});
    } else if (ends(".node")) {
      const std::string base = out.substr(0, out.size() - 5);
      for (const char* e : {".node", ".ele", ".face", ".edge"}) writes.push_back({base + e, "-o " + out});
      writes.push_back({base + ".json", "-o " + out + "'s sidecar of segment names"});
    }
    if (!a.stats.empty()) writes.push_back({a.stats, "--stats " + a.stats});
    if (!a.plc_out.empty()) {
      writes.push_back({a.plc_out, "--plc-out " + a.plc_out});
      writes.push_back({gsse::io::base_of(a.plc_out) + ".json", "--plc-out " + a.plc_out + "'s sidecar of segment names"});
    }
  }
  for (std::size_t w = 0; w < writes.size(); ++w) {
    for (const auto& [path, what] : reads)
      if (same(writes[w].first, path)) {
        const auto& [file, who] = writes[w];
        const bool named = ends_with(who, file.c_str());
        throw std::runtime_error(who + (named ? "" : " (" + file + ")") + " would overwrite " + what + ": choose another name");
      }
    for (std::size_t v = 0; v < w; ++v)
      if (writes[v].second != writes[w].second && same(writes[w].first, writes[v].first))
        throw std::runtime_error(writes[w].second + " and " + writes[v].second + " would both write " + writes[w].first + ": choose another name");
  }
}

/// A usage error found after the input is read (exit status 2, as one found in the arguments).
struct usage_error : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// The verifier's verdict, as --verify and --check print it: problems on stderr; exit status 3 if any.
int verdict(const std::vector<std::string>& problems, bool print, const char* what) {
  if (print) std::printf("%s: %s\n", what, problems.empty() ? "PASS" : "FAIL");
  for (const auto& s : problems) std::fprintf(stderr, "gsse-mesh: %s: %s\n", what, s.c_str());
  return problems.empty() ? 0 : 3;
}

/// --check: an existing mesh against the input PLC.
template <std::size_t D>
int check(const gsse::plc<D>& p, const args& a) {
  const std::string& m = a.check;
  auto ends = [&](const char* e) { return ends_with(m, e); };
  const gsse::domain<D> d = ends(".msh") ? gsse::io::read_msh<D>(m) : gsse::io::read_node_ele<D>(m);
  gsse::verify::options vo;
  vo.threads = a.threads;
  vo.facet_tolerance = a.verify_tol;
  const auto r = gsse::verify::check(d, p, vo);
  if (!a.quiet)
    std::printf("%s against %s: %zu cells, %zu hull and %zu interface faces (%zu on a facet within the tolerance),\n"
                "  %zu components, volume error %.3g, deepest vertex inside a circumsphere %.3g of its squared radius\n",
                m.c_str(), p.source.c_str(), r.cells, r.hull_faces, r.interface_faces, r.inexact_faces, r.components,
                r.volume_error, r.deepest_delaunay);
  return verdict(r.problems, !a.quiet, "check");
}

template <std::size_t D>
int run(const gsse::plc<D>& p, const args& a) {
  if (!a.check.empty()) return check(p, a);
  const bool tty = !a.quiet && isatty(2);
  std::vector<gsse::point<D>> cloud;
  if (!a.cloud.empty()) cloud = gsse::io::read_node<D>(a.cloud);
  gsse::pipeline::options o;
  o.size = a.size;
  o.threads = a.threads;
  o.verify = a.verify;
  o.size_fit = a.size_fit;
  o.size_rounds = a.size_rounds;
  o.gabriel = a.gabriel;
  o.quality = a.quality;
  o.quality_bound = a.quality_bound;
  o.sliver_angle = a.sliver_angle;
  o.cavity_fill = a.cavity_fill;
  o.acute_guard = a.acute_guard;
  o.quality_rounds = a.quality_rounds;
  if (a.quality) {
    // a bound out of range is a usage error (exit 2), found only here: its range is the dimension's
    try {
      gsse::refinement::ratio_bound(D, a.quality_bound);
    } catch (const std::invalid_argument& e) {
      throw usage_error(e.what());
    }
  }
  o.verify_tolerance = a.verify_tol;
  o.conform.max_steiner = a.max_steiner;
  {
    // the size field: the sidecar's sizing keys, the regions' volumes, --grade
    const std::string side = gsse::io::base_of(a.input) + ".json";
    const auto table = gsse::io::read_sidecar(side);
    gsse::sizing::spec<D> sp;
    gsse::sizing::add_sidecar(sp, table.sizing, p, side);
    if (a.grade > 0) sp.grade = a.grade;
    sp.feature_size = !a.no_feature;
    const bool volumes = std::any_of(p.regions.begin(), p.regions.end(), [](const auto& r) { return r.max_volume > 0; });
    o.graded = a.grade > 0 || !table.sizing.empty() || volumes;
    if constexpr (D == 2)
      o.sizing2 = sp;
    else
      o.sizing3 = sp;
  }
  o.conform.merge_coplanar = !a.no_merge;
  // GSSE_CONFORM_TRACE=1: the conformer's rounds on stderr (the library prints nothing itself)
  if (const char* t = std::getenv("GSSE_CONFORM_TRACE"); t && std::string(t) != "0" && *t)
    o.conform.trace = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  gsse::rules::rule_set custom;
  if (!a.rules.empty()) {
    custom = gsse::rules::load_rules(a.rules);
    gsse::rules::require_valid(custom);
    if (custom.dimension != static_cast<int>(D))
      throw std::runtime_error(a.rules + ": a " + std::to_string(custom.dimension) + "D rule set for a " +
                               std::to_string(D) + "D input");
    if (custom.split.rules.empty() && custom.front.rules.empty())
      throw std::runtime_error(a.rules + ": neither split rules nor front rules");
    if (!custom.split.rules.empty()) o.conform.rules = &custom;
    if (!custom.front.rules.empty()) {
      o.front_rules = &custom.front;
      if (a.fill.empty()) o.interior = gsse::pipeline::fill::rules;
    }
  }
  if (a.fill == "rules") o.interior = gsse::pipeline::fill::rules;
  if (o.interior == gsse::pipeline::fill::rules && !(a.size > 0))
    throw std::runtime_error("--fill rules needs --size (the rules work in units of the target size)");
  if (o.interior == gsse::pipeline::fill::rules && a.quality)
    throw std::runtime_error("--quality does not combine with --fill rules (the refinement places the interior points itself)");
  if (o.interior == gsse::pipeline::fill::rules && o.graded)
    throw std::runtime_error("--fill rules works with a uniform --size only, not with graded sizing (--grade, sidecar sizes, region volumes)");
  if (tty) o.progress = [](const std::string& s) { std::fprintf(stderr, "\r\033[Kgsse-mesh: %s", s.c_str()); };
  gsse::pipeline::report r;
  auto d = gsse::pipeline::mesh(p, cloud, o, r);
  if (tty) std::fprintf(stderr, "\r\033[K");
  const std::vector<std::string>& problems = r.problems;
  if (!a.output.empty() && problems.empty()) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string& out = a.output;
    auto ends = [&](const char* e) { return ends_with(out, e); };
    if (ends(".vtu"))
      gsse::io::write_vtu(d, out);
    else if (ends(".msh"))
      gsse::io::write_msh(d, out, false, a.msh22 ? gsse::io::msh_version::v22 : gsse::io::msh_version::v41);
    else if (ends(".node"))
      gsse::io::write_node_ele(d, out.substr(0, out.size() - 5), a.threads);
    else
      throw std::runtime_error(out + ": unknown output format (use .vtu, .msh or .node)");
    r.times.push_back({"write", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
  }
  if ((r.quality || r.size_rounds) && !r.refinement.failure.empty())
    std::fprintf(stderr, "gsse-mesh: warning: %s refinement stopped by a failed %s; the mesh is the round before, %zu elements above the bound\n",
                 r.quality ? "quality" : "size", r.refinement.failure.c_str(), r.refinement.bad_left);
  const auto q = (!a.quiet || !a.stats.empty()) ? gsse::pipeline::measure(d, a.threads) : gsse::pipeline::quality{};
  const double shortest_in = gsse::shortest_input_edge(p);
  if (!a.quiet) {
    std::printf("%s: %zuD, %zu points (%zu volume, %zu dropped outside, %zu boundary Steiner), %zu segments\n",
                p.source.c_str(), D, d.points().size(), r.volume_points, r.dropped_points, r.steiner, d.segments().size());
    if (o.interior == gsse::pipeline::fill::rules) {
      const auto& c = r.creation;
      std::printf("  front rules: %zu points created for %zu faces with a far apex (declined: %zu no rule fits,\n"
                  "               %zu outside, %zu encroaching, %zu in a circumsphere; %zu reused a point)\n",
                  c.created, c.too_far, c.no_rule, c.outside, c.encroaching, c.in_circumball, c.not_needed);
    }
    if (!r.uniform_size)
      std::printf("  sizing: graded (grade %.3g), smallest size %.4g, %zu boundary pieces carry the local terms\n",
                  D == 3 ? o.sizing3.grade : o.sizing2.grade, r.min_size, r.size_sources);
    for (const auto& s : d.segments()) {
      const auto& c = s.cell_data();
      std::vector<gsse::vertex_id> used;
      for (const auto& x : c) used.insert(used.end(), x.begin(), x.end());
      std::sort(used.begin(), used.end());
      used.erase(std::unique(used.begin(), used.end()), used.end());
      std::printf("  segment %2d %-16s %8zu vertices %9zu %s\n", s.number(), s.name().c_str(), used.size(), c.size(),
                  D == 3 ? "tetrahedra" : "triangles");
    }
    std::printf("  quality: radius-edge ratio min %.3f median %.3f max %.3g; %s angle min %.2f max %.2f degrees\n",
                q.min_ratio, q.median_ratio, q.max_ratio, D == 3 ? "dihedral" : "plane", q.min_angle, q.max_angle);
    std::printf("           %zu elements with an angle below 5 degrees, %zu below 10, %zu above 170\n", q.below5, q.below10,
                q.above170);
    if (shortest_in > 0)
      std::printf("           shortest edge %.4g, %.3g times the input's shortest (%.4g)\n", q.shortest_edge,
                  q.shortest_edge / shortest_in, shortest_in);
    std::printf("           radius-edge");
    for (std::size_t k = 0; k < q.ratio_histogram.size(); ++k) {
      if (k < q.ratio_bounds.size())
        std::printf(" <%g: %zu", q.ratio_bounds[k], q.ratio_histogram[k]);
      else
        std::printf(", %g and above: %zu", q.ratio_bounds.back(), q.ratio_histogram[k]);
    }
    std::printf("\n");
    if (r.size_measured) {
      const auto& f = r.size_fit;
      const double all = static_cast<double>(std::max<std::size_t>(f.edges, 1));
      std::printf("  size fit: %zu edges against the size at their midpoints: %.1f%% within [0.5, 1.5] of it, %.1f%% below\n"
                  "           half, %.1f%% above 1.5; ratio min %.3g median %.3g max %.3g\n",
                  f.edges, 100 * static_cast<double>(f.within) / all, 100 * static_cast<double>(f.below_half) / all,
                  100 * static_cast<double>(f.above) / all, f.min_ratio, f.median_ratio, f.max_ratio);
    } else if (a.size_fit) {
      std::printf("  size fit: no size to fit (give --size, --grade or region volumes)\n");
    }
    if (r.quality || r.size_rounds) {
      const auto& st = r.refinement;
      std::printf("  %s: %s after %zu rounds, %zu circumcentres inserted, %zu boundary faces split;\n"
                  "           %zu elements left %s\n",
                  r.quality ? "refinement" : "size rounds (edges above 1.5 h; --no-size-rounds: off)",
                  st.converged ? "converged" : "stopped", st.rounds, st.inserted, st.split_requests, st.bad_left,
                  r.quality ? "above the bound" : "with an edge above 1.5 h");
      if (st.excepted) {
        std::printf("           of those, %zu excepted at small input angles", st.excepted);
        if (st.below_floor) std::printf(" (%zu below the spacing floor)", st.below_floor);
        std::printf(":");
        for (std::size_t k = 0; k < st.excepted_near.size() && k < 4; ++k) {
          const auto& x = d.points()[st.excepted_near[k].first];
          std::printf("%s %zu near the input point (%g", k ? "," : "", st.excepted_near[k].second, x[0]);
          for (std::size_t j = 1; j < D; ++j) std::printf(", %g", x[j]);
          std::printf(")");
        }
        if (st.excepted_near.size() > 4) std::printf(" and %zu more points (--stats lists all)", st.excepted_near.size() - 4);
        std::printf("\n");
      }
      if (st.full_remeshes)
        std::printf("           %zu round%s meshed every segment whole: the cavities did not re-fill (the mesh is right, "
                    "the run slower; please report the input)\n",
                    st.full_remeshes, st.full_remeshes == 1 ? "" : "s");
      if (!st.failure.empty()) std::printf("           stopped by a failed %s (the mesh is the round before)\n", st.failure.c_str());
    }
    for (const auto& t : r.times) std::printf("  %-8s %8.3f s\n", t.stage.c_str(), t.seconds);
  }
  if (!a.stats.empty() && problems.empty()) {  // a failed verification writes no file at all
    std::ofstream js(a.stats);
    js << "{\"points\": " << d.points().size() << ", \"segments\": [";
    for (std::size_t k = 0; k < d.segments().size(); ++k)
      js << (k ? ", " : "") << "{\"name\": \"" << d.segments()[k].name() << "\", \"number\": " << d.segments()[k].number()
         << ", \"cells\": " << d.segments()[k].num_cells() << "}";
    js << "], \"steiner\": " << r.steiner << ", \"boundary_faces\": \"" << (r.delaunay_faces ? "delaunay" : "gabriel")
       << "\", \"volume_points\": " << r.volume_points
       << ", \"created_points\": " << r.creation.created << ", \"malloc\": ";
    // the allocator's settings the run had (apps/allocator_tuning.hpp): GLIBC_TUNABLES, or null
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    js << (tunables ? gsse::io::json_string(tunables) : "null") << ", \"times\": {";
    for (std::size_t k = 0; k < r.times.size(); ++k)
      js << (k ? ", " : "") << "\"" << r.times[k].stage << "\": " << r.times[k].seconds;
    js << "}, \"quality\": {\"elements\": " << q.elements << ", \"radius_edge\": {\"min\": " << q.min_ratio
       << ", \"median\": " << q.median_ratio << ", \"max\": " << q.max_ratio << ", \"histogram\": [";
    for (std::size_t k = 0; k < q.ratio_histogram.size(); ++k)
      js << (k ? ", " : "") << "{\"below\": " << (k < q.ratio_bounds.size() ? std::to_string(q.ratio_bounds[k]) : "null")
         << ", \"elements\": " << q.ratio_histogram[k] << "}";
    js << "]}, \"angle\": {\"min\": " << q.min_angle << ", \"max\": " << q.max_angle << ", \"below_5\": " << q.below5
       << ", \"below_10\": " << q.below10 << ", \"above_170\": " << q.above170 << ", \"smallest_by_10_degrees\": [";
    for (std::size_t k = 0; k < q.angle_histogram.size(); ++k) js << (k ? ", " : "") << q.angle_histogram[k];
    js << "]}, \"edges\": {\"shortest\": " << q.shortest_edge << ", \"shortest_input\": " << shortest_in
       << "}, \"uniform_size\": " << (r.uniform_size ? "true" : "false")
       << ", \"min_size\": " << r.min_size;
    if (r.size_measured) {
      const auto& f = r.size_fit;
      js << ", \"size_fit\": {\"edges\": " << f.edges << ", \"below_half\": " << f.below_half << ", \"within\": " << f.within
         << ", \"above\": " << f.above << ", \"ratio\": {\"min\": " << f.min_ratio << ", \"median\": " << f.median_ratio
         << ", \"max\": " << f.max_ratio << "}, \"histogram\": [";
      for (std::size_t k = 0; k < f.histogram.size(); ++k)
        js << (k ? ", " : "") << "{\"below\": " << (k < f.bounds.size() ? std::to_string(f.bounds[k]) : "null")
           << ", \"edges\": " << f.histogram[k] << "}";
      js << "]}";
    }
    if (r.quality || r.size_rounds) {
      // size rounds: no shape bound ("bound": null), only edges above 1.5 h refined
      js << ", \"refinement\": {\"for\": \"" << (r.quality ? "quality" : "size") << "\", \"bound\": ";
      if (r.quality)
        js << gsse::refinement::ratio_bound(D, a.quality_bound);
      else
        js << "null";
      js << ", \"converged\": "
         << (r.refinement.converged ? "true" : "false") << ", \"rounds\": " << r.refinement.rounds
         << ", \"inserted\": " << r.refinement.inserted << ", \"boundary_splits\": " << r.refinement.split_requests
         << ", \"above_bound\": " << r.refinement.bad_left << ", \"excepted\": " << r.refinement.excepted << ", \"below_floor\": " << r.refinement.below_floor
         << ", \"outside\": " << r.refinement.outside
         << ", \"excepted_near\": [";
      for (std::size_t k = 0; k < r.refinement.excepted_near.size(); ++k) {
        const auto& x = d.points()[r.refinement.excepted_near[k].first];
        js << (k ? ", " : "") << "{\"point\": " << r.refinement.excepted_near[k].first << ", \"at\": [" << x[0];
        for (std::size_t j = 1; j < D; ++j) js << ", " << x[j];
        js << "], \"elements\": " << r.refinement.excepted_near[k].second << "}";
      }
      js << "]"
         << ", \"sliver_angle\": " << (D == 3 && r.quality ? a.sliver_angle : 0.0) << ", \"failed\": " << (r.refinement.failure.empty() ? "false" : "true")
         << ", \"seconds\": {\"plan\": " << r.refinement.plan_seconds << ", \"conform\": " << r.refinement.conform_seconds
         << ", \"label\": " << r.refinement.label_seconds << ", \"mesh\": " << r.refinement.mesh_seconds << "}"
         << ", \"cavity_cells\": " << r.refinement.cavity_cells << ", \"cavity_made\": " << r.refinement.cavity_made
         << ", \"full_remeshes\": " << r.refinement.full_remeshes << ", \"cavity_front_regions\": " << r.refinement.cavity_front_regions
         << ", \"per_round\": [";
      for (std::size_t k = 0; k < r.refinement.per_round.size(); ++k) {
        const auto& x = r.refinement.per_round[k];
        js << (k ? ", " : "") << "{\"bad\": " << x.bad << ", \"inserted\": " << x.inserted << ", \"boundary_splits\": " << x.split_requests
           << ", \"cavity_cells\": " << x.cavity_cells << ", \"cavity_made\": " << x.cavity_made
           << ", \"cavity_front_regions\": " << x.cavity_front_regions << ", \"seconds\": {\"plan\": " << x.plan_seconds
           << ", \"conform\": " << x.conform_seconds << ", \"label\": " << x.label_seconds << ", \"mesh\": " << x.mesh_seconds << "}}";
      }
      js << "]}";
    }
    js << "}";
    js << ", \"verified\": " << (a.verify ? "true" : "null") << "}\n";
  }
  return verdict(problems, a.verify && !a.quiet, "verify");
}

}  // namespace

int main(int argc, char** argv) {
  gsse::apps::tune_allocator(argv);
  args a;
  try {
    // every option but these meshes, writes a mesh or checks one: --plc-out, which meshes nothing,
    // refuses them rather than ignore them
    static const std::set<std::string> not_meshing{"--plc-out", "--threads", "--no-merge", "--quiet", "-h", "--help"};
    for (int i = 1; i < argc; ++i) {
      const std::string s = argv[i];
      if (s.size() > 1 && s[0] == '-' && !not_meshing.count(s)) a.meshing.push_back(s);
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument("option " + s + " needs a value");
        return argv[++i];
      };
      // a finite number taking the whole value ("0.2abc", "abc", "", "inf", "nan" and "1e999" are
      // refused, naming the option)
      auto real = [&](const std::string& v) {
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);  // an overflow gives HUGE_VAL, not finite
        if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(x))
          throw std::invalid_argument(s + ": '" + v + "' is not a finite number");
        return x;
      };
      auto whole = [&](const std::string& v) {
        char* end = nullptr;
        errno = 0;
        const long x = std::strtol(v.c_str(), &end, 10);
        // digits only, a leading minus allowed (strtol would also take "+4" and " 4")
        if (v.empty() || !(std::isdigit(static_cast<unsigned char>(v[0])) || v[0] == '-') || end != v.c_str() + v.size() ||
            errno == ERANGE)
          throw std::invalid_argument(s + ": '" + v + "' is not a whole number");
        return x;
      };
      if (s == "-h" || s == "--help") {
        usage(stdout);
        return 0;
      } else if (s == "-o") {
        a.output = value();
      } else if (s == "--size") {
        a.size = real(value());
        if (!(a.size > 0)) throw std::invalid_argument("--size must be positive");
      } else if (s == "--cloud") {
        a.cloud = value();
      } else if (s == "--threads") {
        const std::string v = value();
        const long n = whole(v);
        if (n < 1 || n > 4096) throw std::invalid_argument("--threads must be a whole number from 1 to 4096, not '" + v + "'");
        a.threads = static_cast<unsigned>(n);
      } else if (s == "--msh") {
        const std::string v = value();
        if (v != "2.2" && v != "4.1") throw std::invalid_argument("--msh must be 4.1 or 2.2, not '" + v + "'");
        a.msh22 = v == "2.2";
      } else if (s == "--stats") {
        a.stats = value();
      } else if (s == "--fill") {
        a.fill = value();
        if (a.fill != "lattice" && a.fill != "rules")
          throw std::invalid_argument("--fill must be 'lattice' or 'rules', not '" + a.fill + "'");
      } else if (s == "--rules") {
        a.rules = value();
      } else if (s == "--plc-out") {
        a.plc_out = value();
        if (a.plc_out.size() < 5 || a.plc_out.compare(a.plc_out.size() - 5, 5, ".poly") != 0)
          throw std::invalid_argument("--plc-out must name a .poly file");
      } else if (s == "--max-steiner") {
        const long n = whole(value());
        if (n < 0) throw std::invalid_argument("--max-steiner must not be negative");
        a.max_steiner = static_cast<std::size_t>(n);
      } else if (s == "--check") {
        a.check = value();
      } else if (s == "--verify-tol") {
        a.verify_tol = real(value());
        if (!(a.verify_tol >= 0 && a.verify_tol < 1)) throw std::invalid_argument("--verify-tol must be in [0, 1)");
        a.verify_tol_given = true;
      } else if (s == "--grade") {
        a.grade = real(value());
        if (!(a.grade > 1) || !std::isfinite(a.grade)) throw std::invalid_argument("--grade must be a number above 1");
      } else if (s == "--quality") {
        a.quality = true;
        // an optional number
        if (i + 1 < argc) {
          char* end = nullptr;
          const double v = std::strtod(argv[i + 1], &end);
          if (end && *end == 0 && end != argv[i + 1]) {
            if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("--quality bound must be a positive number");
            a.quality_bound = v;
            ++i;
          }
        }
      } else if (s == "--quality-rounds") {
        const long n = whole(value());
        if (n < 1 || n > 100000) throw std::invalid_argument("--quality-rounds must be in [1, 100000]");
        a.quality_rounds = static_cast<std::size_t>(n);
      } else if (s == "--acute-guard") {
        a.acute_guard = real(value());
        if (!(a.acute_guard >= 0 && a.acute_guard <= 100)) throw std::invalid_argument("--acute-guard must be in [0, 100]");
      } else if (s == "--cavity-fill") {
        const std::string v = value();
        if (v != "insertion" && v != "front") throw std::invalid_argument("--cavity-fill must be insertion or front");
        a.cavity_fill = v == "front" ? gsse::refinement::cavity_fill::front : gsse::refinement::cavity_fill::insertion;
      } else if (s == "--sliver-angle") {
        a.sliver_angle = real(value());
        if (!(a.sliver_angle >= 0 && a.sliver_angle < 30)) throw std::invalid_argument("--sliver-angle must be in [0, 30)");
      } else if (s == "--no-feature-size") {
        a.no_feature = true;
      } else if (s == "--size-fit") {
        a.size_fit = true;
      } else if (s == "--no-size-rounds") {
        a.size_rounds = false;
      } else if (s == "--verify") {
        a.verify = true;
      } else if (s == "--no-merge") {
        a.no_merge = true;
      } else if (s == "--gabriel") {
        a.gabriel = true;
      } else if (s == "--quiet") {
        a.quiet = true;
      } else if (!s.empty() && s[0] == '-') {
        throw std::invalid_argument("unknown option '" + s + "'");
      } else if (a.input.empty()) {
        a.input = s;
      } else {
        throw std::invalid_argument("more than one input given");
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gsse-mesh: %s\n", e.what());
    usage(stderr);
    return 2;
  }
  if (a.input.empty()) {
    usage(stderr);
    return 2;
  }
  if (a.verify_tol_given && a.check.empty()) a.verify = true;  // --verify-tol implies --verify
  if (!a.check.empty() && (!a.output.empty() || !a.stats.empty() || !a.cloud.empty() || a.size > 0 || a.verify || a.size_fit)) {
    std::fprintf(stderr, "gsse-mesh: --check verifies an existing mesh: it takes none of -o, --stats, --cloud, --size, --verify, --size-fit\n");
    usage(stderr);
    return 2;
  }
  if (!a.plc_out.empty() && !a.meshing.empty()) {
    std::string given;
    for (const auto& m : a.meshing) given += (given.empty() ? "" : ", ") + m;
    std::fprintf(stderr, "gsse-mesh: --plc-out writes the input as read and meshes nothing: it takes no option but --threads, --no-merge and --quiet (given: %s)\n", given.c_str());
    usage(stderr);
    return 2;
  }
  if (!a.output.empty()) {  // before meshing: an unknown format would be found out only at the end
    const auto dot = a.output.rfind('.');
    const std::string e = dot == std::string::npos ? "" : a.output.substr(dot);
    if (e != ".vtu" && e != ".msh" && e != ".node") {
      std::fprintf(stderr, "gsse-mesh: %s: unknown output format '%s' (use .vtu, .msh or .node)\n", a.output.c_str(), e.c_str());
      usage(stderr);
      return 2;
    }
  }
  try {
    refuse_overwrites(a);
    std::vector<gsse::io::plc_volume> volumes;
    auto input = gsse::io::read_plc(a.input, &volumes);
    if (!volumes.empty()) {
      auto& p3 = std::get<gsse::plc<3>>(input);
      for (const auto& s : gsse::plc_tools::drop_stray_facets(p3, volumes, a.threads))
        std::fprintf(stderr, "gsse-mesh: warning: %s:%zu: facet %zu and %zu more connected to it bound no volume and lie outside every volume: left out\n",
                     a.input.c_str(), s.line, s.facet + 1, s.facets - 1);
      gsse::plc_tools::add_region_points(p3, volumes, a.threads);
    }
    if (!a.plc_out.empty()) {
      if (auto* p3 = std::get_if<gsse::plc<3>>(&input))
        gsse::io::write_tetgen_poly(*p3, a.plc_out);
      else
        gsse::io::write_triangle_poly(std::get<gsse::plc<2>>(input), a.plc_out);
      return 0;
    }
    return std::visit([&](const auto& p) { return run(p, a); }, input);
  } catch (const usage_error& e) {
    std::fprintf(stderr, "gsse-mesh: %s\n", e.what());
    usage(stderr);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gsse-mesh: error: %s\n", e.what());
    return 1;
  }
}
