#pragma once
/// \file detail/convex_search.h
/// Internal: the one-dimensional convex search behind the primitives' box and hull tests
/// (primitives.cpp). A cone's solid, the convex hull of its two balls, is the union of the
/// balls B(c(t), r(t)) with c and r linear in t in [0, 1]; it meets a box exactly when the
/// convex function box_distance(c(t)) - r(t) reaches 0 on [0, 1].

#include <Eigen/Core>

#include <algorithm>
#include <limits>

namespace mg::garbing::detail {

/// A golden-section bracket [a, b] of a convex function's minimum, with its two inner samples
/// and the least sample seen.
template <class F>
struct GoldenBracket {
  static constexpr double g = 0.6180339887498949;
  const F& f;
  double a, b, x1, x2, f1, f2, best;

  GoldenBracket(const F& fn, double lo, double hi)
      : f(fn), a(lo), b(hi), x1(hi - g * (hi - lo)), x2(lo + g * (hi - lo)) {
    f1 = f(x1);
    f2 = f(x2);
    best = std::min({f(lo), f(hi), f1, f2});
  }

  /// Narrows the bracket by the golden ratio, one new sample.
  void step() {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
      best = std::min(best, f1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
      best = std::min(best, f2);
    }
  }
};

/// Whether a convex function f on [0, 1], its slope bounded by `lipschitz`, reaches <= 0:
/// golden section that stops as soon as a sample is <= 0 (yes) or the bound from the
/// bracket, min sample - lipschitz * width, is > 0 (no); a width of 1e-9 counts as yes, so the
/// answer errs only toward "reaches".
template <class F>
bool convex_reaches_zero(const F& f, double lipschitz) {
  GoldenBracket<F> s(f, 0.0, 1.0);
  // The minimum lies in [0, 1]; the bound needs the bracket that holds it.
  while (s.best > 0) {
    if (s.best - lipschitz * (s.b - s.a) > 0) return false;
    if (s.b - s.a <= 1e-9) return true;
    s.step();
  }
  return true;
}

/// The minimum of a convex function f on [a, b] with slope bound `lipschitz`, from below: golden
/// section to a width of 1e-9 (b - a), the least sample minus lipschitz times that width. Stops
/// early at the first sample <= stop_at and returns it (then not a bound, only a witness).
template <class F>
double convex_minimum_below(const F& f, double a, double b, double lipschitz,
                            double stop_at = -std::numeric_limits<double>::infinity()) {
  if (!(b > a)) return f(a);
  const double width = 1e-9 * (b - a);
  GoldenBracket<F> s(f, a, b);
  while (s.b - s.a > width) {
    if (s.best <= stop_at) return s.best;
    s.step();
  }
  return s.best - lipschitz * (s.b - s.a);
}

/// Whether a convex function f(s, t) on the triangle s, t >= 0, s + t <= 1, its slope along
/// either parameter bounded by `lipschitz`, reaches <= 0: the partial minimum over t in
/// [0, 1 - s] is convex in s; each is searched from below, so the answer errs only toward
/// "reaches".
template <class F>
bool convex_reaches_zero_on_triangle(const F& f, double lipschitz) {
  return convex_reaches_zero(
      [&](double s) {
        return convex_minimum_below([&](double t) { return f(s, t); }, 0.0, 1 - s, lipschitz, 0.0);
      },
      2 * lipschitz);
}

}  // namespace mg::garbing::detail
