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

/// Whether a convex function f on [0, 1], its slope bounded by `lipschitz`, reaches <= 0:
/// golden section that stops as soon as a sample is <= 0 (yes) or the bound from the
/// bracket, min sample - lipschitz * width, is > 0 (no); a width of 1e-9 counts as yes, so the
/// answer errs only toward "reaches".
template <class F>
bool convex_reaches_zero(const F& f, double lipschitz) {
  constexpr double g = 0.6180339887498949;
  double a = 0, b = 1;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  double best = std::min({f(0.0), f(1.0), f1, f2});
  // The minimum lies in [0, 1]; the bound needs the bracket that holds it.
  while (best > 0) {
    if (best - lipschitz * (b - a) > 0) return false;
    if (b - a <= 1e-9) return true;
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
  return true;
}

/// The minimum of a convex function f on [a, b] with slope bound `lipschitz`, from below: golden
/// section to a width of 1e-9 (b - a), the least sample minus lipschitz times that width. Stops
/// early at the first sample <= stop_at and returns it (then not a bound, only a witness).
template <class F>
double convex_minimum_below(const F& f, double a, double b, double lipschitz,
                            double stop_at = -std::numeric_limits<double>::infinity()) {
  constexpr double g = 0.6180339887498949;
  if (!(b > a)) return f(a);
  const double width = 1e-9 * (b - a);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  double best = std::min({f(a), f(b), f1, f2});
  while (b - a > width) {
    if (best <= stop_at) return best;
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
  return best - lipschitz * (b - a);
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
