#pragma once
// Default segment model: a named, numbered simplicial complex (one material region) with its
// quantities. Cells hold domain-wide vertex ids, so vertices along an interface are shared by
// every segment that meets there.
#include <string>
#include <utility>

#include "gsse/container/simplicial_complex.hpp"
#include "gsse/quantity/quantity.hpp"

namespace gsse {

template <std::size_t D>
class segment : public simplicial_complex<D> {
 public:
  segment() = default;
  segment(std::string name, int number) : name_(std::move(name)), number_(number) {}

  const std::string& name() const { return name_; }
  int number() const { return number_; }
  void set_name(std::string n) { name_ = std::move(n); }
  void set_number(int n) { number_ = n; }

  quantity_store& quantities() { return q_; }
  const quantity_store& quantities() const { return q_; }
  /// Number of vertex slots vertex quantities provide (the domain's point count when owned by one).
  std::size_t vertex_slots() const { return std::max<std::size_t>(vertex_slots_, this->vertex_extent()); }
  void set_vertex_slots(std::size_t n) { vertex_slots_ = n; }

 private:
  std::string name_;
  int number_ = 0;
  quantity_store q_;
  std::size_t vertex_slots_ = 0;
};

}  // namespace gsse
