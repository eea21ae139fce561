#pragma once
// A foreign mesh type, as a research code might have it: flat coordinate and connectivity arrays
// and a region tag per cell. It is adapted to gsse's Domain/Segment/CellComplex concepts purely by
// free functions in its own namespace (found by ADL), without changing the type. The conformance
// suite runs on it exactly as on gsse::domain.
#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "gsse/gsse.hpp"

namespace legacy {

template <std::size_t D>
struct mesh {
  std::vector<double> xyz;         // D coordinates per point
  std::vector<int> conn;           // D+1 point numbers per cell
  std::vector<int> region;         // region tag per cell
};

/// A view of one region: local cell numbers, neighbours within the region, vertex-to-cell map.
template <std::size_t D>
class region_view {
 public:
  static constexpr std::size_t dimension = D;
  region_view(const mesh<D>* m, int tag) : m_(m), tag_(tag), name_("region" + std::to_string(tag)) {
    for (std::size_t c = 0; c < m->region.size(); ++c)
      if (m->region[c] == tag) cells_.push_back(c);
    nbr_.assign(cells_.size(), {});
    std::map<std::vector<int>, std::pair<std::size_t, int>> open;
    for (std::size_t lc = 0; lc < cells_.size(); ++lc) {
      nbr_[lc].fill(gsse::no_cell);
      for (int i = 0; i <= static_cast<int>(D); ++i) {
        std::vector<int> key;
        for (int j = 0; j <= static_cast<int>(D); ++j)
          if (j != i) key.push_back(m->conn[cells_[lc] * (D + 1) + static_cast<std::size_t>(j)]);
        std::sort(key.begin(), key.end());
        auto [it, fresh] = open.try_emplace(key, lc, i);
        if (!fresh) {
          nbr_[lc][static_cast<std::size_t>(i)] = static_cast<gsse::cell_id>(it->second.first);
          nbr_[it->second.first][static_cast<std::size_t>(it->second.second)] = static_cast<gsse::cell_id>(lc);
        }
      }
      for (int j = 0; j <= static_cast<int>(D); ++j)
        around_[m->conn[cells_[lc] * (D + 1) + static_cast<std::size_t>(j)]].push_back(static_cast<gsse::cell_id>(lc));
    }
  }
  friend std::size_t num_cells(const region_view& r) { return r.cells_.size(); }
  friend std::array<gsse::vertex_id, D + 1> vertices(const region_view& r, gsse::cell_id c) {
    std::array<gsse::vertex_id, D + 1> v;
    for (std::size_t j = 0; j <= D; ++j) v[j] = static_cast<gsse::vertex_id>(r.m_->conn[r.cells_[c] * (D + 1) + j]);
    return v;
  }
  friend gsse::cell_id neighbour(const region_view& r, gsse::cell_id c, int i) {
    return r.nbr_[c][static_cast<std::size_t>(i)];
  }
  friend const std::vector<gsse::cell_id>& cells(const region_view& r, gsse::vertex_id v) {
    static const std::vector<gsse::cell_id> none;
    auto it = r.around_.find(static_cast<int>(v));
    return it == r.around_.end() ? none : it->second;
  }
  friend const std::string& name(const region_view& r) { return r.name_; }
  friend int number(const region_view& r) { return r.tag_; }

 private:
  const mesh<D>* m_;
  int tag_;
  std::string name_;
  std::vector<std::size_t> cells_;
  std::vector<std::array<gsse::cell_id, D + 1>> nbr_;
  std::map<int, std::vector<gsse::cell_id>> around_;
};

/// The adapted domain: the mesh plus one view per region tag.
template <std::size_t D>
struct adapted {
  static constexpr std::size_t dimension = D;
  explicit adapted(const mesh<D>& m) : m_(&m) {
    std::vector<int> tags(m.region);
    std::sort(tags.begin(), tags.end());
    tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
    for (int t : tags) views_.emplace_back(&m, t);
  }
  friend std::size_t num_points(const adapted& a) { return a.m_->xyz.size() / D; }
  friend gsse::point<D> position(const adapted& a, gsse::vertex_id v) {
    gsse::point<D> p;
    for (std::size_t k = 0; k < D; ++k) p[k] = a.m_->xyz[v * D + k];
    return p;
  }
  friend const std::vector<region_view<D>>& segments(const adapted& a) { return a.views_; }

 private:
  const mesh<D>* m_;
  std::vector<region_view<D>> views_;
};

static_assert(gsse::cell_complex<region_view<2>> && gsse::segment_model<region_view<3>>);
static_assert(gsse::domain_model<adapted<2>> && gsse::domain_model<adapted<3>>);

}  // namespace legacy
