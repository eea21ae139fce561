#pragma once
// Quantities: data on the vertices or cells of a segment, kept outside the topology and reached
// through typed handles. A handle is a slot number plus the value and location types, so the
// access path is an index into a std::vector<T>: no string lookup, no type test. Names are kept
// only for I/O and for finding a quantity once (find_quantity).
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

namespace gsse {

struct on_vertices_t {
  static constexpr bool cells = false;
};
struct on_cells_t {
  static constexpr bool cells = true;
};
inline constexpr on_vertices_t on_vertices{};
inline constexpr on_cells_t on_cells{};

/// Typed handle of a quantity of T on location Loc (on_vertices_t or on_cells_t).
template <class T, class Loc>
struct quantity {
  using value_type = T;
  using location = Loc;
  std::uint32_t slot = 0;
  friend bool operator==(quantity, quantity) = default;
};

/// Type-erased columns of one segment. Vertex columns are indexed by the domain-wide vertex id,
/// cell columns by the segment's cell id (see docs/design-decisions.md for the trade-off).
class quantity_store {
 public:
  struct info {
    std::string name;
    const std::type_info* type;
    bool on_cells;
  };

  quantity_store() = default;
  quantity_store(const quantity_store& o) { *this = o; }
  quantity_store(quantity_store&&) noexcept = default;
  quantity_store& operator=(quantity_store&&) noexcept = default;
  quantity_store& operator=(const quantity_store& o) {
    if (this == &o) return *this;
    cols_.clear();
    for (const auto& c : o.cols_) cols_.push_back(c->clone());
    return *this;
  }

  template <class T, class Loc>
  quantity<T, Loc> add(std::string name, std::size_t size, T init) {
    for (const auto& c : cols_)
      if (c->meta.name == name && c->meta.on_cells == Loc::cells)
        throw std::invalid_argument("quantity '" + name + "' exists already");
    auto col = std::make_unique<column<T>>();
    col->meta = {std::move(name), &typeid(T), Loc::cells};
    col->init = init;
    col->data.assign(size, init);
    cols_.push_back(std::move(col));
    return {static_cast<std::uint32_t>(cols_.size() - 1)};
  }

  template <class T, class Loc>
  std::optional<quantity<T, Loc>> find(std::string_view name) const {
    for (std::size_t i = 0; i < cols_.size(); ++i) {
      const auto& m = cols_[i]->meta;
      if (m.name == name && m.on_cells == Loc::cells && *m.type == typeid(T))
        return quantity<T, Loc>{static_cast<std::uint32_t>(i)};
    }
    return std::nullopt;
  }

  /// The column of handle q, grown (with the initial value) to at least `size` entries.
  template <class T, class Loc>
  std::vector<T>& column_of(quantity<T, Loc> q, std::size_t size) {
    auto& c = static_cast<column<T>&>(*cols_.at(q.slot));
    if (c.data.size() < size) c.data.resize(size, c.init);
    return c.data;
  }
  template <class T, class Loc>
  const std::vector<T>& column_of(quantity<T, Loc> q) const {
    return static_cast<const column<T>&>(*cols_.at(q.slot)).data;
  }

  std::size_t size() const { return cols_.size(); }
  const info& meta(std::size_t slot) const { return cols_.at(slot)->meta; }
  /// Raw access for I/O: pointer to the first element and element count of a double/int column.
  template <class T>
  const std::vector<T>* typed(std::size_t slot) const {
    const auto& c = *cols_.at(slot);
    if (*c.meta.type != typeid(T)) return nullptr;
    return &static_cast<const column<T>&>(c).data;
  }
  void resize_cells(std::size_t n) {
    for (auto& c : cols_)
      if (c->meta.on_cells) c->resize(n);
  }

 private:
  struct column_base {
    info meta{};
    virtual ~column_base() = default;
    virtual std::unique_ptr<column_base> clone() const = 0;
    virtual void resize(std::size_t n) = 0;
  };
  template <class T>
  struct column final : column_base {
    std::vector<T> data;
    T init{};
    std::unique_ptr<column_base> clone() const override { return std::make_unique<column<T>>(*this); }
    void resize(std::size_t n) override { data.resize(n, init); }
  };
  std::vector<std::unique_ptr<column_base>> cols_;
};

}  // namespace gsse
