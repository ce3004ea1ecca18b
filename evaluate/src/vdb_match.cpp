// Voxel-size searches for the OpenVDB baseline (no OpenVDB code here: vdb_mesh() does that).
#include "evaluate/vdb_mesh.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>

namespace mg::evaluate {
namespace {

/// Finds h with measure(vdb_mesh(h)) ~ target, in x = ln h, y = ln(measure / target).
class VoxelSearch {
 public:
  /// @param exponent  the model's d ln(measure) / d ln h before two probes give a slope
  VoxelSearch(const MedialSurface& atoms, garbing::PrimitiveSet primitives, double target,
              double exponent, std::function<double(const VdbMesh&)> measure, int max_probes)
      : atoms_(atoms),
        primitives_(primitives),
        target_(target),
        exponent_(exponent),
        measure_(std::move(measure)),
        max_probes_(max_probes) {
    if (max_probes < 1 || max_probes > 20)
      throw InvalidInput("voxel search: probes must be in [1, 20], got " +
                         std::to_string(max_probes));
    validate(atoms);
    if (garbing::resolve(primitives, atoms) == garbing::PrimitiveSet::envelope)
      envelope_ = std::make_unique<garbing::TargetShape>(
          garbing::make_target_shape(atoms, garbing::PrimitiveSet::envelope, {}));
    const double diagonal = spheres_bbox_diagonal(atoms);
    x_min_ = std::log(diagonal / 2000);
    x_max_ = std::log(diagonal / 20);
  }

  VdbMatch run() {
    VdbMatch result;
    double best_error = std::numeric_limits<double>::infinity();
    double x = std::log(spheres_bbox_diagonal(atoms_) / 400);
    for (int probe = 0; probe < max_probes_; ++probe) {
      if (x < x_min_ || x > x_max_) {
        result.clamped = true;
        x = std::clamp(x, x_min_, x_max_);
      }
      if (std::any_of(xs_.begin(), xs_.end(), [&](double xi) { return std::abs(xi - x) < 1e-9; }))
        break;  // clamped onto a voxel already tried: no progress possible
      VdbOptions opt;
      opt.voxel = std::exp(x);
      opt.primitives = primitives_;
      VdbMesh mesh = envelope_ ? vdb_mesh(*envelope_, opt) : vdb_mesh(atoms_, opt);
      const double value = measure_(mesh);
      const double y = std::log(std::max(value, 1e-300) / target_);
      result.probes.push_back({mesh.voxel, value, mesh.mesh.points.size()});
      xs_.push_back(x);
      ys_.push_back(y);
      if (std::abs(y) < best_error) {
        best_error = std::abs(y);
        result.best = std::move(mesh);
        result.value = value;
      }
      if (std::abs(value / target_ - 1) <= 0.01) break;
      x = next_x();
    }
    return result;
  }

 private:
  double next_x() const {
    // Bracket: the probes on either side of the target closest to it.
    int above = -1, below = -1;
    for (std::size_t i = 0; i < ys_.size(); ++i) {
      if (ys_[i] > 0 && (above < 0 || ys_[i] < ys_[above])) above = static_cast<int>(i);
      if (ys_[i] < 0 && (below < 0 || ys_[i] > ys_[below])) below = static_cast<int>(i);
    }
    if (above >= 0 && below >= 0) {
      const double xa = xs_[above], ya = ys_[above], xb = xs_[below], yb = ys_[below];
      const double secant = xa - ya * (xb - xa) / (yb - ya);
      const double lo = std::min(xa, xb), hi = std::max(xa, xb), margin = 0.05 * (hi - lo);
      if (secant > lo + margin && secant < hi - margin) return secant;
      return 0.5 * (lo + hi);  // bisection
    }
    double slope = exponent_;
    const std::size_t n = xs_.size();
    if (n >= 2) {
      const double s = (ys_[n - 1] - ys_[n - 2]) / (xs_[n - 1] - xs_[n - 2]);
      if (std::isfinite(s) && s * exponent_ > 0 && std::abs(s) > 0.1 * std::abs(exponent_))
        slope = s;
    }
    const double max_step = std::log(8.0);
    return xs_.back() + std::clamp(-ys_.back() / slope, -max_step, max_step);
  }

  const MedialSurface& atoms_;
  garbing::PrimitiveSet primitives_;
  std::unique_ptr<garbing::TargetShape> envelope_;  // G, built once, on the envelope's path
  double target_, exponent_;
  std::function<double(const VdbMesh&)> measure_;
  int max_probes_;
  double x_min_ = 0, x_max_ = 0;
  std::vector<double> xs_, ys_;
};

}  // namespace

VdbMatch vdb_match_vertices(const MedialSurface& atoms, std::size_t vertices, int max_probes,
                            garbing::PrimitiveSet primitives) {
  if (vertices < 1) throw InvalidInput("--match-vertices must be >= 1");
  return VoxelSearch(
             atoms, primitives, static_cast<double>(vertices), /*exponent=*/-2.0,
             [](const VdbMesh& m) { return static_cast<double>(m.mesh.points.size()); }, max_probes)
      .run();
}

VdbMatch vdb_match_hausdorff(const MedialSurface& atoms, double percent,
                             const PolygonSoup& reference, const MeshDistanceOptions& distance,
                             const std::string& reference_name, int max_probes,
                             garbing::PrimitiveSet primitives) {
  if (!(percent > 0) || !std::isfinite(percent)) {
    std::ostringstream m;
    m << "--match-hausdorff percent must be > 0, got " << percent;
    throw InvalidInput(m.str());
  }
  return VoxelSearch(
             atoms, primitives, percent, /*exponent=*/1.0,
             [&](const VdbMesh& m) {
               MeshDistanceOptions opt = distance;
               if (opt.samples > 0 && opt.vertices_and_edges)  // Metro takes every vertex
                 opt.samples =
                     std::max({opt.samples, 2 * m.mesh.points.size(), 2 * reference.points.size()});
               const MeshDistance d =
                   mesh_distance(m.mesh, reference, opt, "vdb mesh", reference_name);
               return percent_of_diagonal(d.distance.hausdorff, d.diagonal);
             },
             max_probes)
      .run();
}

}  // namespace mg::evaluate
