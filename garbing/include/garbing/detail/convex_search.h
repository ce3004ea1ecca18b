#pragma once
/// \file detail/convex_search.h
/// Internal: the one-dimensional convex search behind the primitives' box and hull tests
/// (primitives.cpp). A cone's solid, the convex hull of its two balls, is the union of the
/// balls B(c(t), r(t)) with c and r linear in t in [0, 1]; it meets a box exactly when the
/// convex function box_distance(c(t)) - r(t) reaches 0 on [0, 1].

#include <Eigen/Core>

#include <algorithm>

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

}  // namespace mg::garbing::detail
