// The reference job of bench/cloud_scaling.sh: CGAL's Delaunay_triangulation_3 (GPL, benchmark
// only) of the points of a TetGen .node file, read and written as TetGen files the way gsse-mesh
// reads and writes them (.node in, .node/.ele out, shortest round-trip decimals), on one thread.
// usage: cgal_delaunay IN.node OUT_BASENAME   -> prints one JSON line with the stage times
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <charconv>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<unsigned, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Whitespace-separated tokens of a line, '#' comments dropped.
std::vector<std::string_view> tokens(std::string_view l) {
  if (const auto h = l.find('#'); h != std::string_view::npos) l = l.substr(0, h);
  std::vector<std::string_view> t;
  std::size_t i = 0;
  while (i < l.size()) {
    while (i < l.size() && (l[i] == ' ' || l[i] == '\t' || l[i] == '\r')) ++i;
    const std::size_t j = i;
    while (i < l.size() && l[i] != ' ' && l[i] != '\t' && l[i] != '\r') ++i;
    if (i > j) t.push_back(l.substr(j, i - j));
  }
  return t;
}

double real(std::string_view s) {
  double x = 0;
  std::from_chars(s.data(), s.data() + s.size(), x);
  return x;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: cgal_delaunay IN.node OUT_BASENAME\n");
    return 2;
  }
  auto t0 = std::chrono::steady_clock::now();
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string data = ss.str();
  std::vector<std::pair<K::Point_3, unsigned>> pts;
  std::size_t pos = 0, n = 0;
  bool header = true;
  while (pos < data.size()) {
    std::size_t e = data.find('\n', pos);
    if (e == std::string::npos) e = data.size();
    const auto t = tokens(std::string_view(data).substr(pos, e - pos));
    pos = e + 1;
    if (t.empty()) continue;
    if (header) {
      n = static_cast<std::size_t>(real(t[0]));
      pts.reserve(n);
      header = false;
    } else if (pts.size() < n && t.size() >= 4) {
      pts.push_back({K::Point_3(real(t[1]), real(t[2]), real(t[3])), static_cast<unsigned>(pts.size())});
    }
  }
  const double read = since(t0);
  t0 = std::chrono::steady_clock::now();
  DT dt(pts.begin(), pts.end());
  const double build = since(t0);
  t0 = std::chrono::steady_clock::now();
  {
    std::string out;
    char buf[32];
    out += std::to_string(pts.size()) + " 3 0 0\n";
    for (const auto& [p, i] : pts) {
      out += std::to_string(i + 1);
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        out.append(buf, std::to_chars(buf, buf + sizeof buf, p[k]).ptr);
      }
      out += '\n';
    }
    std::ofstream(std::string(argv[2]) + ".node", std::ios::binary) << out;
    out.clear();
    out += std::to_string(dt.number_of_finite_cells()) + " 4 0\n";
    std::size_t k = 0;
    for (auto c : dt.finite_cell_handles()) {
      out += std::to_string(++k);
      for (int j = 0; j < 4; ++j) out += ' ' + std::to_string(c->vertex(j)->info() + 1);
      out += '\n';
    }
    std::ofstream(std::string(argv[2]) + ".ele", std::ios::binary) << out;
  }
  const double write = since(t0);
  std::printf("{\"points\": %zu, \"tetrahedra\": %zu, \"read\": %.3f, \"build\": %.3f, \"write\": %.3f, \"total\": %.3f}\n",
              pts.size(), dt.number_of_finite_cells(), read, build, write, read + build + write);
}
