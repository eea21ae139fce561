#pragma once
// Points: plain arrays of doubles. User point structs are accepted through Boost.Fusion
// (BOOST_FUSION_ADAPT_STRUCT), the one place where Fusion earns its keep: C++20 has no
// reflection to walk the members of a foreign struct.
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include <boost/fusion/include/at_c.hpp>
#include <boost/fusion/include/size.hpp>
#include <boost/fusion/support/is_sequence.hpp>

namespace gsse {

template <std::size_t D>
using point = std::array<double, D>;
using point2 = point<2>;
using point3 = point<3>;

/// Concept: a user type adapted as a Fusion sequence of D arithmetic members.
template <class P, std::size_t D>
concept fusion_point = boost::fusion::traits::is_sequence<P>::value &&
                       (boost::fusion::result_of::size<P>::type::value == D);

/// Converts any Fusion-adapted point struct (or a gsse::point) to gsse::point<D>.
template <std::size_t D, class P>
  requires fusion_point<P, D> || std::is_same_v<std::remove_cvref_t<P>, point<D>>
point<D> to_point(const P& p) {
  if constexpr (std::is_same_v<std::remove_cvref_t<P>, point<D>>) {
    return p;
  } else {
    point<D> r{};
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      ((r[I] = static_cast<double>(boost::fusion::at_c<I>(p))), ...);
    }(std::make_index_sequence<D>{});
    return r;
  }
}

template <std::size_t D>
point<D> operator-(const point<D>& a, const point<D>& b) {
  point<D> r;
  for (std::size_t i = 0; i < D; ++i) r[i] = a[i] - b[i];
  return r;
}
template <std::size_t D>
point<D> operator+(const point<D>& a, const point<D>& b) {
  point<D> r;
  for (std::size_t i = 0; i < D; ++i) r[i] = a[i] + b[i];
  return r;
}
template <std::size_t D>
point<D> operator*(double s, const point<D>& a) {
  point<D> r;
  for (std::size_t i = 0; i < D; ++i) r[i] = s * a[i];
  return r;
}
template <std::size_t D>
double dot(const point<D>& a, const point<D>& b) {
  double s = 0;
  for (std::size_t i = 0; i < D; ++i) s += a[i] * b[i];
  return s;
}
inline point3 cross(const point3& a, const point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <std::size_t D>
double squared_distance(const point<D>& a, const point<D>& b) {
  const auto d = a - b;
  return dot(d, d);
}
template <std::size_t D>
double distance(const point<D>& a, const point<D>& b) {
  return std::sqrt(squared_distance(a, b));
}
template <std::size_t D>
bool is_finite(const point<D>& p) {
  for (double x : p)
    if (!std::isfinite(x)) return false;
  return true;
}

/// The global order used by the symbolic perturbation: lexicographic on coordinates.
template <std::size_t D>
bool lex_less(const point<D>& a, const point<D>& b) {
  for (std::size_t i = 0; i < D; ++i) {
    if (a[i] < b[i]) return true;
    if (b[i] < a[i]) return false;
  }
  return false;
}

}  // namespace gsse
