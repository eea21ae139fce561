#pragma once
// Exact signs of the orientation and in-sphere determinants for the common case in which every
// coordinate difference the determinant is built from is itself a double and all of them are
// integer multiples of one power of two 2^e with at most 61 bits each (the points lie close
// together, away from zero: a lattice, a facet's subdivision points, a small cavity). Axis-aligned
// structures put many vertices exactly on common spheres and planes (a lattice cube's 8 corners),
// and there the exact answer is 0: every floating-point filter fails and CGAL's exact fallback
// (multi-precision Mpzf) cost about 0.8 microseconds a call, 17% of meshing the bench trench.
// Here the differences are read as 61-bit integers (times 2^e, which does not change a sign)
// and the determinant is evaluated in fixed-width integers of 64-bit limbs: exact, no allocation.
// Where the differences are not doubles (points made by front rules or as circumcentres, whose
// coordinates differ in magnitude by more than a factor 2), the points are first moved together
// by an exact translation and their coordinates read as integers (integer_rows): near ties there
// went to Mpzf, about half of a `--fill rules` run, until 2026-12-03.
//
// The double filters assume round-to-nearest, as CGAL's static filters do.
// Every function returns the exact sign, as CGAL's predicates do, or `undecided` (2) when the
// differences do not fit; the caller then asks CGAL. The answers are the same either way, so the
// meshes are too (tests/core/predicates_test.cpp compares both on lattices and random input).
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "gsse/geometry/point.hpp"

// The exactness tests (a two-sum's tail) and the filters' error bounds assume IEEE arithmetic
// as written: value-changing optimisations would make the signs wrong.
#if defined(__FAST_MATH__)
#error "gsse/geometry/fixed_predicates.hpp needs IEEE floating point: do not compile it with -ffast-math"
#endif

namespace gsse::geometry::fixed {

inline constexpr int undecided = 2;

namespace detail {
inline constexpr double eps = 0x1p-53;  // the unit roundoff
using u64 = std::uint64_t;
__extension__ typedef unsigned __int128 u128;
__extension__ typedef __int128 i128;

/// Magnitudes: little-endian limbs. Two's complement accumulators: the same with the top bit as sign.
template <std::size_t N>
using limbs = std::array<u64, N>;

template <std::size_t A, std::size_t B>
limbs<A + B> mul(const limbs<A>& x, const limbs<B>& y) {
  limbs<A + B> r{};
  for (std::size_t i = 0; i < A; ++i) {
    u64 carry = 0;
    for (std::size_t j = 0; j < B; ++j) {
      const u128 t = static_cast<u128>(x[i]) * y[j] + r[i + j] + carry;
      r[i + j] = static_cast<u64>(t);
      carry = static_cast<u64>(t >> 64);
    }
    r[i + B] = carry;
  }
  return r;
}
/// acc += (negative ? -m : m), acc in two's complement of N limbs (M <= N, no overflow by range).
template <std::size_t N, std::size_t M>
void accumulate(limbs<N>& acc, const limbs<M>& m, bool negative) {
  static_assert(M <= N);
  if (!negative) {
    u64 carry = 0;
    for (std::size_t i = 0; i < N; ++i) {
      const u128 t = static_cast<u128>(acc[i]) + (i < M ? m[i] : 0) + carry;
      acc[i] = static_cast<u64>(t);
      carry = static_cast<u64>(t >> 64);
    }
  } else {
    u64 borrow = 0;
    for (std::size_t i = 0; i < N; ++i) {
      const u64 s = i < M ? m[i] : 0;
      const u128 t = static_cast<u128>(acc[i]) - s - borrow;
      acc[i] = static_cast<u64>(t);
      borrow = static_cast<u64>(t >> 64) ? 1 : 0;
    }
  }
}
template <std::size_t N>
int sign(const limbs<N>& acc) {
  if (static_cast<std::int64_t>(acc[N - 1]) < 0) return -1;
  for (u64 x : acc)
    if (x != 0) return 1;
  return 0;
}
/// |acc| into M limbs (|acc| < 2^(64 M) by range) and its sign.
template <std::size_t M, std::size_t N>
limbs<M> magnitude(limbs<N> acc, int& s) {
  s = sign(acc);
  if (s < 0) {  // negate: invert and add one
    u64 carry = 1;
    for (auto& x : acc) {
      const u128 t = static_cast<u128>(~x) + carry;
      x = static_cast<u64>(t);
      carry = static_cast<u64>(t >> 64);
    }
  }
  limbs<M> r{};
  for (std::size_t i = 0; i < M; ++i) r[i] = acc[i];
  return r;
}
inline limbs<2> mag128(i128 v, bool& negative) {
  negative = v < 0;
  const u128 m = negative ? static_cast<u128>(-v) : static_cast<u128>(v);
  return {static_cast<u64>(m), static_cast<u64>(m >> 64)};
}

/// x (exactly a double) as mant * 2^ex with mant odd (mant 0 for 0): false if x is subnormal,
/// infinite or NaN.
inline bool odd_parts(double x, u64& mant, int& ex, int& top) {
  mant = 0, ex = 0, top = 0;
  if (x == 0) return true;
  const u64 bits = std::bit_cast<u64>(x);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased == 0 || biased == 0x7ff) return false;
  const u64 m = (bits & ((u64{1} << 52) - 1)) | (u64{1} << 52);
  const int z = std::countr_zero(m);
  mant = m >> z;
  ex = biased - 1075 + z;  // the lowest set bit
  top = ex + 52 - z;       // the highest
  return true;
}
/// a - b, and whether that is exact (the error-free difference's tail is zero).
inline bool exact_difference(double a, double b, double& x) {
  x = a - b;
  const double bv = a - x, av = x + bv;
  return (a - av) + (bv - b) == 0;
}
/// Exact doubles v[j][k] (none subnormal) as integers times one 2^e, each below 2^(span + 1):
/// false if they need more bits than that at the scale of the smallest set bit among them.
template <std::size_t M>
bool to_integers(const std::array<std::array<double, 3>, M>& v, int span, std::array<std::array<std::int64_t, 3>, M>& out) {
  std::array<std::array<u64, 3>, M> mant{};
  std::array<std::array<int, 3>, M> ex{};
  int lowest = 1 << 20, highest = -(1 << 20);
  for (std::size_t i = 0; i < M; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      int top;
      if (!odd_parts(v[i][k], mant[i][k], ex[i][k], top)) return false;
      if (mant[i][k] == 0) continue;
      lowest = std::min(lowest, ex[i][k]);
      highest = std::max(highest, top);
    }
  if (highest < lowest) {  // all zero
    out = {};
    return true;
  }
  if (highest - lowest > span) return false;
  for (std::size_t i = 0; i < M; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto x = mant[i][k] == 0 ? 0 : static_cast<std::int64_t>(mant[i][k] << (ex[i][k] - lowest));
      out[i][k] = v[i][k] < 0 ? -x : x;
    }
  return true;
}

/// The differences a - o for each a in `pts` as integers times 2^e (one e for all), each below
/// 2^61: false if they do not fit (or a coordinate is subnormal, infinite or NaN).
/// First the differences themselves, where each is exactly a double and they fit in 61 bits at
/// the scale of the smallest set bit among them (a lattice, a facet's subdivision points). Else
/// the points and o moved together by t, per axis 0 or a multiple of the power of two s just
/// above their spread (each moved coordinate is checked exact; any t would do for the sign, this
/// one makes them exact and small), each moved coordinate read as an integer below 2^60 at the
/// scale of the smallest set bit among them, and the rows their differences, exactly: a
/// translation changes none of the signs. On an axis far from 0 (|o| >= 2s) the differences are
/// exact already; moving it matters where such an axis meets one near 0, whose coordinates'
/// last bits lie far below the far axis's top. It fails when the lowest set bit of all lies more
/// than 59 bits below the highest moved coordinate (up to about 3s): a generic coordinate on an
/// axis near 0 smaller than about 2^-6 of the spread, or 0 next to such a one (points made by a
/// front rule, circumcentres, a rotated input's vertices mostly fit: near ties among them went
/// to CGAL's multi-precision fallback, about half of a `--fill rules` run).
template <std::size_t N>
bool integer_rows(const std::array<const point3*, N>& pts, const point3& o, std::array<std::array<std::int64_t, 3>, N>& rows) {
  {
    std::array<std::array<double, 3>, N> d;
    bool exact = true;
    for (std::size_t i = 0; i < N && exact; ++i)
      for (std::size_t k = 0; k < 3 && exact; ++k) exact = exact_difference((*pts[i])[k], o[k], d[i][k]);
    if (exact && to_integers<N>(d, 60, rows)) return true;
  }
  double spread = 0;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t k = 0; k < 3; ++k) spread = std::max(spread, std::abs((*pts[i])[k] - o[k]));
  if (!(spread > 0) || !(spread < 0x1p900)) return false;  // an infinite o too; a NaN fails exact_difference below
  int e;
  std::frexp(spread, &e);
  const double s = std::ldexp(1.0, e);  // a power of two above the spread
  std::array<std::array<double, 3>, N + 1> v;  // the points, then o, moved by t
  for (std::size_t k = 0; k < 3; ++k) {
    // a coordinate below 2s stays where it is (moved by a multiple of s it could only grow and
    // lose its last bits); else every one on this axis is at least s, their last bits at or
    // above s 2^-52, and minus the multiple of s nearest o, at most 1.5 s: exact
    const double t = std::abs(o[k]) < 2 * s ? 0.0 : std::nearbyint(o[k] / s) * s;  // exact: s is a power of two
    for (std::size_t i = 0; i <= N; ++i)
      if (!exact_difference(i < N ? (*pts[i])[k] : o[k], t, v[i][k])) return false;
  }
  std::array<std::array<std::int64_t, 3>, N + 1> w;
  if (!to_integers<N + 1>(v, 59, w)) return false;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t k = 0; k < 3; ++k) rows[i][k] = w[i][k] - w[N][k];
  return true;
}

/// Whether the double filters' error bounds hold for these difference vectors: every non-zero
/// entry at least 2^-140. Then every product of up to six entries (the longest term, in
/// in_equatorial) is at least 2^-840, a normal double, so a product can underflow only after a
/// cancellation, and its absolute error (at most 2^-1075) is a vanishing fraction of the
/// permanent, which counts that term's magnitudes before the cancellation. Without the check an
/// underflowed product later multiplied by a huge entry can exceed the bound (a review found
/// orient3d, in_sphere and in_equatorial giving the wrong sign with entries of 2^-540 beside
/// 2^1000). Overflow needs no check: it makes the permanent infinite, which the filters reject.
template <std::size_t N>
bool filter_safe(const std::array<point3, N>& rows) {
  // on the bits of |x|: 0 < |x| < 2^-140 is (bits - 1) < bits(2^-140) - 1 unsigned (0 wraps
  // above, NaN and infinities lie above too); one pass without branches
  constexpr u64 below = std::bit_cast<u64>(0x1p-140) - 1;
  bool tiny = false;
  for (const auto& r : rows)
    for (double x : r) tiny |= (std::bit_cast<u64>(x) & ~(u64{1} << 63)) - 1 < below;
  return !tiny;
}

/// |x| and sign of an int64 as one limb.
inline limbs<1> mag64(std::int64_t v, bool& negative) {
  negative = v < 0;
  return {negative ? static_cast<u64>(0) - static_cast<u64>(v) : static_cast<u64>(v)};
}

/// Exactly q_j s_k - q_k s_j (|.| < 2^123 for 61-bit entries).
inline i128 cross2(std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) {
  return static_cast<i128>(a) * b - static_cast<i128>(c) * d;
}
/// Exactly det[p; q; s] (|.| < 2^187) in two's complement of 4 limbs.
inline limbs<4> det3(const std::array<std::int64_t, 3>& p, const std::array<std::int64_t, 3>& q,
                     const std::array<std::int64_t, 3>& s) {
  const i128 m[3] = {cross2(q[1], s[2], q[2], s[1]), cross2(q[2], s[0], q[0], s[2]), cross2(q[0], s[1], q[1], s[0])};
  limbs<4> acc{};
  for (std::size_t k = 0; k < 3; ++k) {
    if (p[k] == 0 || m[k] == 0) continue;
    bool nm, np;
    const limbs<2> mm = mag128(m[k], nm);
    const limbs<1> mp = mag64(p[k], np);
    accumulate(acc, mul(mm, mp), nm != np);
  }
  return acc;
}
/// det[x; y; z] in doubles, and its permanent (the same expression on absolute values, no more
/// roundings) for the filters' error bounds.
inline double det3_double(const point3& x, const point3& y, const point3& z, double& perm) {
  perm = std::abs(x[0]) * (std::abs(y[1] * z[2]) + std::abs(y[2] * z[1])) +
         std::abs(x[1]) * (std::abs(y[2] * z[0]) + std::abs(y[0] * z[2])) +
         std::abs(x[2]) * (std::abs(y[0] * z[1]) + std::abs(y[1] * z[0]));
  return x[0] * (y[1] * z[2] - y[2] * z[1]) + x[1] * (y[2] * z[0] - y[0] * z[2]) + x[2] * (y[0] * z[1] - y[1] * z[0]);
}
}  // namespace detail

/// Sign of orient3d(a, b, c, d) (+1: d on the side (b-a)x(c-a) points to), as CGAL's orientation:
/// the determinant of the rows b-a, c-a, d-a.
inline int orient3d(const point3& a, const point3& b, const point3& c, const point3& d) {
  using namespace detail;
  // a double filter first (round to nearest): along any term, 3 rounded entries, 2 roundings in
  // a 2x2 minor, 1 in the scaling, 2 in the sum: |error| <= gamma_8 * permanent, and 16 eps
  // covers that and the permanent's own rounding (filter_safe: no underflow spoils it)
  const std::array<point3, 3> rows = {b - a, c - a, d - a};
  double perm;
  const double det = det3_double(rows[0], rows[1], rows[2], perm);
  if (std::abs(det) > 16 * eps * perm && std::isfinite(perm) && filter_safe(rows)) return det > 0 ? 1 : -1;
  std::array<std::array<std::int64_t, 3>, 3> r;
  if (!integer_rows<3>({&b, &c, &d}, a, r)) return undecided;
  return sign(det3(r[0], r[1], r[2]));
}

/// Sign of in_sphere(a, b, c, d, e) as CGAL's side_of_oriented_sphere: +1 if e lies inside the
/// sphere of the positive tetrahedron abcd.
inline int in_sphere(const point3& a, const point3& b, const point3& c, const point3& d, const point3& e) {
  using namespace detail;
  {  // a double filter first: along any term, 5 rounded entries, 3 roundings in |r_i|^2, 5 in a
     // minor, 1 in the product, 3 in the sum: gamma_17 < 18 eps of the permanent; 32 eps covers
     // that and the permanent's own rounding
    const std::array<point3, 4> p = {a - e, b - e, c - e, d - e};
    double P[4];
    const double M[4] = {det3_double(p[1], p[2], p[3], P[0]), det3_double(p[0], p[2], p[3], P[1]),
                         det3_double(p[0], p[1], p[3], P[2]), det3_double(p[0], p[1], p[2], P[3])};
    double w[4];
    for (std::size_t i = 0; i < 4; ++i) w[i] = p[i][0] * p[i][0] + p[i][1] * p[i][1] + p[i][2] * p[i][2];
    const double det = -w[0] * M[0] + w[1] * M[1] - w[2] * M[2] + w[3] * M[3];
    const double perm = w[0] * P[0] + w[1] * P[1] + w[2] * P[2] + w[3] * P[3];
    if (std::abs(det) > 32 * eps * perm && std::isfinite(perm) && filter_safe(p)) return det > 0 ? -1 : 1;
  }
  std::array<std::array<std::int64_t, 3>, 4> r;
  if (!integer_rows<4>({&a, &b, &c, &d}, e, r)) return undecided;
  // det of the lifted rows (r_i, |r_i|^2) = -w0 M0 + w1 M1 - w2 M2 + w3 M3, M_i the 3x3
  // determinant of the other rows in order; CGAL's test is the opposite sign (its rows are a, c,
  // b, d: checked in the tests). |w| < 2^124, |M| < 2^187, the sum < 2^314: 6 limbs hold it.
  constexpr std::size_t others[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  limbs<6> acc{};
  for (std::size_t i = 0; i < 4; ++i) {
    int ms;
    const limbs<3> M = magnitude<3>(det3(r[others[i][0]], r[others[i][1]], r[others[i][2]]), ms);
    if (ms == 0) continue;
    u128 w = 0;
    for (std::size_t k = 0; k < 3; ++k) w += static_cast<u128>(static_cast<i128>(r[i][k]) * r[i][k]);
    if (w == 0) continue;
    const limbs<2> ww{static_cast<u64>(w), static_cast<u64>(w >> 64)};
    // term sign: (-1)^(i+1) * sign(M); CGAL's sign is the opposite, accumulated directly
    const bool term_negative = (i % 2 == 0) != (ms < 0);
    accumulate(acc, mul(ww, M), !term_negative);
  }
  return sign(acc);
}

/// Sign of in_equatorial(a, b, c, t) as CGAL's side_of_bounded_sphere with four points: +1 if t
/// lies inside the ball whose equator is the circumcircle of abc, 0 on its sphere, -1 outside
/// (abc not collinear). With u = b - a, v = c - a, w = t - a, n = u x v, that ball's centre is
/// a + N / (2 |n|^2), N = |u|^2 (v x n) + |v|^2 (n x u), so the sign is that of N.w - |n|^2 |w|^2
/// (degree 6: |.| < 2^375 for 61-bit entries, 7 limbs).
inline int in_equatorial(const point3& a, const point3& b, const point3& c, const point3& t) {
  using namespace detail;
  {  // a double filter first: along any term at most 19 roundings (entries 1, |u|^2 5, v x n 7,
     // the products and sums 6): gamma_19 < 20 eps of the permanent; 64 eps covers that and the
     // permanent's own rounding
    const std::array<point3, 3> rows = {b - a, c - a, t - a};
    const point3 &u = rows[0], &v = rows[1], &w = rows[2];
    const point3 n = cross(u, v);
    const point3 an{std::abs(u[1] * v[2]) + std::abs(u[2] * v[1]), std::abs(u[2] * v[0]) + std::abs(u[0] * v[2]),
                    std::abs(u[0] * v[1]) + std::abs(u[1] * v[0])};
    const point3 vn = cross(v, n), nu = cross(n, u);
    const point3 avn{std::abs(v[1]) * an[2] + std::abs(v[2]) * an[1], std::abs(v[2]) * an[0] + std::abs(v[0]) * an[2],
                     std::abs(v[0]) * an[1] + std::abs(v[1]) * an[0]};
    const point3 anu{an[1] * std::abs(u[2]) + an[2] * std::abs(u[1]), an[2] * std::abs(u[0]) + an[0] * std::abs(u[2]),
                     an[0] * std::abs(u[1]) + an[1] * std::abs(u[0])};
    const double uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
    double lhs = 0, plhs = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      lhs += (uu * vn[k] + vv * nu[k]) * w[k];
      plhs += (uu * avn[k] + vv * anu[k]) * std::abs(w[k]);
    }
    const double nn = dot(n, n), pnn = dot(an, an);
    const double det = lhs - nn * ww, perm = plhs + pnn * ww;
    if (std::abs(det) > 64 * eps * perm && std::isfinite(perm) && filter_safe(rows)) return det > 0 ? 1 : -1;
  }
  std::array<std::array<std::int64_t, 3>, 3> r;
  if (!integer_rows<3>({&b, &c, &t}, a, r)) return undecided;
  const auto &u = r[0], &v = r[1], &w = r[2];
  const i128 n[3] = {cross2(u[1], v[2], u[2], v[1]), cross2(u[2], v[0], u[0], v[2]), cross2(u[0], v[1], u[1], v[0])};
  // x * y_k for an int64 x and an i128 y, into a signed accumulator
  auto add_product = [](limbs<4>& acc, std::int64_t x, i128 y, bool minus) {
    if (x == 0 || y == 0) return;
    bool nx, ny;
    const limbs<1> mx = mag64(x, nx);
    const limbs<2> my = mag128(y, ny);
    accumulate(acc, mul(mx, my), (nx != ny) != minus);
  };
  auto norm2 = [](const std::array<std::int64_t, 3>& x) {
    u128 s = 0;
    for (std::size_t k = 0; k < 3; ++k) s += static_cast<u128>(static_cast<i128>(x[k]) * x[k]);
    return limbs<2>{static_cast<u64>(s), static_cast<u64>(s >> 64)};
  };
  const limbs<2> uu = norm2(u), vv = norm2(v), ww = norm2(w);
  limbs<7> acc{};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    if (w[k] == 0) continue;
    limbs<4> vn{}, nu{};  // (v x n)_k and (n x u)_k, |.| < 2^186
    add_product(vn, v[k1], n[k2], false);
    add_product(vn, v[k2], n[k1], true);
    add_product(nu, u[k2], n[k1], false);
    add_product(nu, u[k1], n[k2], true);
    limbs<6> Nk{};  // |u|^2 (v x n)_k + |v|^2 (n x u)_k, |.| < 2^311
    int s1, s2;
    const limbs<3> m1 = magnitude<3>(vn, s1), m2 = magnitude<3>(nu, s2);
    if (s1 != 0) accumulate(Nk, mul(uu, m1), s1 < 0);
    if (s2 != 0) accumulate(Nk, mul(vv, m2), s2 < 0);
    int sN;
    const limbs<5> mN = magnitude<5>(Nk, sN);
    if (sN == 0) continue;
    bool nw;
    const limbs<1> mw = mag64(w[k], nw);
    accumulate(acc, mul(mN, mw), (sN < 0) != nw);
  }
  // - |n|^2 |w|^2
  limbs<5> nn{};
  for (std::size_t k = 0; k < 3; ++k) {
    bool neg;
    const limbs<2> m = mag128(n[k], neg);
    accumulate(nn, mul(m, m), false);
  }
  int snn;
  const limbs<4> mnn = magnitude<4>(nn, snn);
  accumulate(acc, mul(mnn, ww), true);
  return sign(acc);
}

}  // namespace gsse::geometry::fixed
