#pragma once
// Hash table of the open faces of the front, keyed by sorted vertices, holding the oriented
// vertices. Linear probing with backward-shift deletion: closed faces leave the table, so it stays
// the size of the front (cache-resident) instead of growing with the mesh.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "gsse/topology/simplex.hpp"

namespace gsse::front {

template <std::size_t N>
class face_table {
 public:
  using face = std::array<vertex_id, N>;
  struct entry {
    face key;       // sorted vertices; key[0] == no_vertex marks an empty slot
    face oriented;  // as stored: the unmeshed side is its positive side
  };

  explicit face_table(std::size_t expected = 64) { rehash(std::max<std::size_t>(64, expected * 2)); }

  static face sorted(face f) {
    std::sort(f.begin(), f.end());
    return f;
  }
  /// The entry of face f (any orientation), or nullptr.
  entry* find(const face& f) {
    const face k = sorted(f);
    for (std::size_t i = hash(k) & mask_;; i = (i + 1) & mask_) {
      if (slots_[i].key[0] == no_vertex) return nullptr;
      if (slots_[i].key == k) return &slots_[i];
    }
  }
  /// Inserts f as open; f must not be present.
  entry* insert(const face& f) {
    if (2 * (size_ + 1) > slots_.size()) rehash(slots_.size() * 2);
    const face k = sorted(f);
    std::size_t i = hash(k) & mask_;
    while (slots_[i].key[0] != no_vertex) i = (i + 1) & mask_;
    slots_[i] = {k, f};
    ++size_;
    return &slots_[i];
  }
  /// Removes the entry e points to (from find).
  void erase(entry* e) {
    std::size_t i = static_cast<std::size_t>(e - slots_.data());
    for (std::size_t j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      if (slots_[j].key[0] == no_vertex) break;
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
  static std::size_t hash(const face& k) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (auto v : k) {
      h ^= v;
      h *= 0xBF58476D1CE4E5B9ull;
      h ^= h >> 29;
    }
    return static_cast<std::size_t>(h);
  }
  void rehash(std::size_t n) {
    std::size_t cap = 64;
    while (cap < n) cap *= 2;
    std::vector<entry> old = std::move(slots_);
    entry empty{};
    empty.key.fill(no_vertex);
    slots_.assign(cap, empty);
    mask_ = cap - 1;
    size_ = 0;
    for (const auto& e : old)
      if (e.key[0] != no_vertex) {
        std::size_t i = hash(e.key) & mask_;
        while (slots_[i].key[0] != no_vertex) i = (i + 1) & mask_;
        slots_[i] = e;
        ++size_;
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
