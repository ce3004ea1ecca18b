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

/// The envelope's G when `primitives` resolves to it on these atoms (built once, for every
/// probe), else null: the spheres' path. @throws InvalidInput when the atoms are invalid
std::unique_ptr<const garbing::TargetShape> envelope_of(const MedialSurface& atoms,
                                                        garbing::PrimitiveSet primitives) {
  validate(atoms);
  if (garbing::resolve(primitives, atoms) != garbing::PrimitiveSet::envelope) return nullptr;
  return std::make_unique<const garbing::TargetShape>(
      garbing::make_target_shape(atoms, garbing::PrimitiveSet::envelope, {}));
}

/// Finds h with measure(vdb_mesh(h)) ~ target, in x = ln h, y = ln(measure / target).
class VoxelSearch {
 public:
  /// @param envelope  G of the envelope (envelope_of), meshed at every probe; null: the spheres
  /// @param exponent  the model's d ln(measure) / d ln h before two probes give a slope
  /// @param stop_when_stalled  stop as out_of_reach when the measure does not follow the voxel
  ///        (the distance to G, which has a floor on the spheres' path); the vertex count and the
  ///        distance to a reference go on probing: the latter is noisy and not monotone in h, and
  ///        its matches in the reproduction's tables come from the full search
  VoxelSearch(const MedialSurface& atoms, const garbing::TargetShape* envelope, double target,
              double exponent, std::function<double(const VdbMesh&)> measure, int max_probes,
              bool stop_when_stalled)
      : atoms_(atoms),
        envelope_(envelope),
        target_(target),
        exponent_(exponent),
        measure_(std::move(measure)),
        max_probes_(max_probes),
        stop_when_stalled_(stop_when_stalled) {
    if (max_probes < 1 || max_probes > 20)
      throw InvalidInput("voxel search: probes must be in [1, 20], got " +
                         std::to_string(max_probes));
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
      opt.primitives = garbing::PrimitiveSet::atoms;  // the spheres' path, when no envelope
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
      if (stop_when_stalled_ && stalled()) {
        result.out_of_reach = true;
        break;
      }
      x = next_x();
    }
    return result;
  }

 private:
  /// The last step, of at least 25% in h and toward the target by the model, moved the measure
  /// less than a tenth of the model's prediction toward it (or away), both probes on one side:
  /// a floor (or ceiling) the voxel does not move, as the cones of G that spheres alone never
  /// fill. Smaller steps are left to noise (H varies by some % between close voxels).
  bool stalled() const {
    const std::size_t n = xs_.size();
    if (n < 2 || ys_[n - 1] * ys_[n - 2] <= 0) return false;
    const double dx = xs_[n - 1] - xs_[n - 2], predicted = exponent_ * dx;
    if (std::abs(dx) < std::log(1.25) || predicted * ys_[n - 2] >= 0) return false;
    return (ys_[n - 1] - ys_[n - 2]) / predicted < 0.1;
  }

  double next_x() const {
    // Bracket: the probes on either side of the target closest to it.
    int above = -1, below = -1;
    for (std::size_t i = 0; i < ys_.size(); ++i) {
      if (ys_[i] > 0 && (above < 0 || ys_[i] < ys_[above])) above = static_cast<int>(i);
      if (ys_[i] < 0 && (below < 0 || ys_[i] > ys_[below])) below = static_cast<int>(i);
    }
    if (above >= 0 && below >= 0) {
      const double xa = xs_[above], ya = ys_[above], xb = xs_[below], yb = ys_[below];
      // The secant through the two always falls inside the bracket; bisection only when it
      // would nearly repeat an end. (A margin of 5% of the bracket bisected away from near hits
      // whose other end was a distant first probe: the capsule's envelope at 0.2%, 1.1% off at
      // probe 2, then three probes of bisection, each farther off.)
      const double secant = xa - ya * (xb - xa) / (yb - ya);
      const double lo = std::min(xa, xb), hi = std::max(xa, xb), margin = 1e-3 * (hi - lo);
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
  const garbing::TargetShape* envelope_;  // G, built once, on the envelope's path; else null
  double target_, exponent_;
  std::function<double(const VdbMesh&)> measure_;
  int max_probes_;
  bool stop_when_stalled_;
  double x_min_ = 0, x_max_ = 0;
  std::vector<double> xs_, ys_;
};

}  // namespace

VdbMatch vdb_match_vertices(const MedialSurface& atoms, std::size_t vertices, int max_probes,
                            garbing::PrimitiveSet primitives) {
  if (vertices < 1) throw InvalidInput("--match-vertices must be >= 1");
  const auto envelope = envelope_of(atoms, primitives);
  return VoxelSearch(
             atoms, envelope.get(), static_cast<double>(vertices), /*exponent=*/-2.0,
             [](const VdbMesh& m) { return static_cast<double>(m.mesh.points.size()); }, max_probes,
             /*stop_when_stalled=*/false)
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
  const auto envelope = envelope_of(atoms, primitives);
  return VoxelSearch(
             atoms, envelope.get(), percent, /*exponent=*/1.0,
             [&](const VdbMesh& m) {
               MeshDistanceOptions opt = distance;
               if (opt.samples > 0 && opt.vertices_and_edges)  // Metro takes every vertex
                 opt.samples =
                     std::max({opt.samples, 2 * m.mesh.points.size(), 2 * reference.points.size()});
               const MeshDistance d =
                   mesh_distance(m.mesh, reference, opt, "vdb mesh", reference_name);
               return percent_of_diagonal(d.distance.hausdorff, d.diagonal);
             },
             max_probes, /*stop_when_stalled=*/false)
      .run();
}

VdbMatch vdb_match_envelope(const MedialSurface& atoms, double percent, double diagonal,
                            const AtomsDistanceOptions& distance, int max_probes) {
  if (!(percent > 0) || !std::isfinite(percent)) {
    std::ostringstream m;
    m << "--match-envelope percent must be > 0, got " << percent;
    throw InvalidInput(m.str());
  }
  if (!(diagonal >= 0) || !std::isfinite(diagonal)) {
    std::ostringstream m;
    m << "--diagonal must be >= 0 and finite, got " << diagonal;
    throw InvalidInput(m.str());
  }
  const auto envelope = envelope_of(atoms, distance.primitives);
  // On the spheres' path G is measured, not meshed: the balls and the chosen cones, as
  // atoms_distance(mesh, atoms, distance) builds it.
  std::unique_ptr<const garbing::TargetShape> balls_and_cones;
  if (!envelope)
    balls_and_cones = std::make_unique<const garbing::TargetShape>(
        garbing::make_target_shape(atoms, garbing::PrimitiveSet::atoms, distance.cones));
  const garbing::TargetShape& g = envelope ? *envelope : *balls_and_cones;
  const double d = diagonal > 0 ? diagonal : spheres_bbox_diagonal(atoms);
  return VoxelSearch(
             atoms, envelope.get(), percent, /*exponent=*/1.0,
             [&](const VdbMesh& m) {
               AtomsDistanceOptions opt = distance;
               if (opt.samples > 0)  // Metro takes every vertex
                 opt.samples = std::max(opt.samples, 2 * m.mesh.points.size());
               const AtomsDistance r = atoms_distance(m.mesh, g, opt, "vdb mesh");
               return percent_of_diagonal(r.distance.hausdorff, d);
             },
             max_probes, /*stop_when_stalled=*/true)
      .run();
}

}  // namespace mg::evaluate
