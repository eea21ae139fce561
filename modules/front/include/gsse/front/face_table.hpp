#pragma once
// Hash table of the open faces of the front, keyed by sorted vertices plus the parity of the
// orientation (16 bytes a triangle, 12 an edge): a face and its reverse are different entries, so a
// constraint with the region on both sides (an embedded facet or edge) is two open faces. Linear probing with backward-shift
// deletion: closed faces leave the table, so it stays the size of the front instead of growing
// with the mesh. A lookup that misses returns the empty slot where the face belongs, so closing
// or opening a face probes once.
#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "gsse/topology/simplex.hpp"

namespace gsse::front {

template <std::size_t N>
class face_table {
 public:
  using face = std::array<vertex_id, N>;
  struct entry {
    face key;             // sorted vertices; key[0] == no_vertex marks an empty slot
    std::uint32_t odd;    // 1 if the stored orientation is an odd permutation of key
    bool empty() const { return key[0] == no_vertex; }
  };

  explicit face_table(std::size_t expected = 64) { rehash(std::max<std::size_t>(64, expected * 2)); }

  /// Sorted vertices of f; `odd` tells whether sorting took an odd permutation.
  static face sorted(face f, std::uint32_t& odd) {
    odd = 0;
    auto order = [&](std::size_t i, std::size_t j) {
      if (f[i] > f[j]) std::swap(f[i], f[j]), odd ^= 1;
    };
    if constexpr (N == 2) {
      order(0, 1);
    } else {
      static_assert(N == 3);
      order(0, 1), order(1, 2), order(0, 1);
    }
    return f;
  }
  /// The entry of face f (this orientation) or, if absent, the empty slot where it belongs (valid
  /// until the next insertion or erasure).
  entry* probe(const face& f) {
    std::uint32_t odd;
    const face k = sorted(f, odd);
    for (std::size_t i = hash(k) & mask_;; i = (i + 1) & mask_) {
      entry& e = slots_[i];
      if (e.empty() || (e.odd == odd && same_key(e.key, k))) return &e;
    }
  }
  /// Hints the cache to load the slot where face f would be probed first.
  void prefetch(const face& f) const {
    std::uint32_t odd;
    __builtin_prefetch(&slots_[hash(sorted(f, odd)) & mask_]);
  }
  /// The entry of face f (this orientation), or nullptr.
  entry* find(const face& f) {
    entry* e = probe(f);
    return e->empty() ? nullptr : e;
  }
  /// True if g has the orientation stored in e.
  static bool same_orientation(const entry& e, const face& g) {
    std::uint32_t odd;
    sorted(g, odd);
    return odd == e.odd;
  }
  /// Stores f (oriented) in the empty slot `at` returned by probe(f).
  void fill(entry* at, const face& f) {
    at->key = sorted(f, at->odd);
    ++size_;
    if (2 * size_ > slots_.size()) rehash(slots_.size() * 2);
  }
  /// Removes the entry e points to (from find or probe).
  void erase(entry* e) {
    std::size_t i = static_cast<std::size_t>(e - slots_.data());
    for (std::size_t j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      if (slots_[j].empty()) break;
      const std::size_t h = hash(slots_[j].key) & mask_;
      // slot j's entry may move to i if i lies cyclically within [h, j)
      if (((j - h) & mask_) >= ((j - i) & mask_)) {
        slots_[i] = slots_[j];
        i = j;
      }
    }
    slots_[i].key[0] = no_vertex;
    --size_;
  }
  std::size_t size() const { return size_; }

 private:
  static bool same_key(const face& a, const face& b) {
    bool eq = true;
    for (std::size_t i = 0; i < N; ++i) eq &= a[i] == b[i];
    return eq;
  }
  static std::size_t hash(const face& k) {
    std::uint64_t h = 0;
    for (auto v : k) h = (h ^ v) * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
  void rehash(std::size_t n) {
    std::size_t cap = 64;
    while (cap < n) cap *= 2;
    std::vector<entry> old = std::move(slots_);
    entry none{};
    none.key.fill(no_vertex);
    slots_.assign(cap, none);
    mask_ = cap - 1;
    for (const auto& e : old)
      if (!e.empty()) {
        std::size_t i = hash(e.key) & mask_;
        while (!slots_[i].empty()) i = (i + 1) & mask_;
        slots_[i] = e;
      }
  }
  std::vector<entry> slots_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

/// True if b lists the vertices of a in an orientation-preserving order (even permutation).
template <std::size_t N>
bool same_orientation(const std::array<vertex_id, N>& a, const std::array<vertex_id, N>& b) {
  if constexpr (N == 2) {
    return a == b;
  } else {
    // b is a rotation of a
    for (std::size_t r = 0; r < N; ++r) {
      bool eq = true;
      for (std::size_t i = 0; i < N && eq; ++i) eq = a[i] == b[(i + r) % N];
      if (eq) return true;
    }
    return false;
  }
}

}  // namespace gsse::front
