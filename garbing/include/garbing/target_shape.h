#pragma once
/// \file target_shape.h
/// The target shape G of the garbing (ALGORITHM.md "Step 3"): the boundary of the union of
/// the primitives P — every atom's sphere, plus for chosen intersecting pairs of atoms the cone
/// tangent to both (cone and spheres together form the pair's convex hull).
/// Queries are exact for spheres and cones; a bounding-volume hierarchy over the primitives'
/// boxes is the broad phase.

#include "garbing/medial_surface.h"

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace mg {

/// Which pairs of atoms get a cone.
enum class ConeSource {
  regular_triangulation,  ///< pairs adjacent in the regular triangulation (weights r^2)
  all_pairs,              ///< every intersecting pair (the paper; quadratic on pole skeletons)
  ma_edges,               ///< the `.ma` file's edges
  none                    ///< spheres only
};

struct ConeOptions {
  ConeSource source = ConeSource::regular_triangulation;
  /// Keep a cone only if the two spheres' intersection circle has a radius of at least this
  /// fraction of the smaller sphere's radius (0 keeps every intersecting pair; 1 keeps none
  /// but concentric spheres). Cones of barely intersecting balls bridge
  /// concavities: chords across the 60 x 20 torus's hole take H(G, O) from 0.30% (neighbour
  /// cones only) to 1.09% with every regular-triangulation cone. Default 0.9, chosen by
  /// measuring H(G, O) over the reference models (results/cone_filter.md).
  double min_circle_ratio = 0.9;
  /// Keep a cone only if its lateral surface stands off the crease of its two spheres (the
  /// circle where they meet) by at most this many rc / 8 (the automatic leaf side bound;
  /// rc = (rmin + rmax) / 2, from the atoms alone); 0: no limit. Deep crease fills are where
  /// G strays from the object most. Default 1, chosen with the circle ratio by measuring
  /// H(G, O) (results/cone_filter.md). (It also once kept the migration from folding across
  /// crease fills, before the octree wrapped the cones.)
  double max_collar = 1;
};

/// Parses "rt", "all", "edges" or "none". @throws InvalidInput
ConeSource parse_cone_source(const std::string& name);

/// The pairs (i < j) that get a cone: from `opt.source`, kept when the two balls intersect,
/// neither contains the other, and the circle-ratio filter passes. Sorted.
/// @pre atoms valid   @throws InvalidInput
std::vector<std::array<int, 2>> cone_pairs(const MedialSurface& atoms, const ConeOptions& opt);

/// The solid cone tangent to two intersecting balls (c1, r1), (c2, r2), L > |r1 - r2|: the
/// truncated cone between the two tangent circles. Axial coordinate t from c1 along u.
struct Cone {
  int a = -1, b = -1;        ///< atom indices
  Eigen::Vector3d c1, u;     ///< first centre, unit axis toward the second
  double r1 = 0, length = 0; ///< first radius, L = |c2 - c1|
  double r2 = 0;             ///< second radius
  double sin_phi = 0, cos_phi = 1;  ///< sin(phi) = (r1 - r2) / L
  double t_lo = 0, t_hi = 0;        ///< axial range of the lateral surface
  double rho_lo = 0, rho_hi = 0;    ///< its radius at t_lo and t_hi
  /// A ball holding the frustum: centred on the axis midway between t_lo and t_hi, through
  /// its rims (squared radius); a cheap rejection for ray tests.
  Eigen::Vector3d bound_centre = Eigen::Vector3d::Zero();
  double bound_radius2 = 0;
};

/// Builds the cone of atoms a and b. @pre the balls intersect and neither contains the other
Cone make_cone(const MedialAtom& first, const MedialAtom& second, int a, int b);

/// min over t in [0, 1] of |p - c(t)| - r(t), c and r linear from (c1, r1) to (c2, r2): the
/// distance from p to the cone's solid (the convex hull of its two balls) when p is outside
/// it; when inside, minus the depth of p in the deepest ball B(c(t), r(t)), a lower bound on
/// its depth in the solid. Closed form: the stationary t has the foot of p on the axis ahead
/// of c(t) by tan(phi) times p's distance from the axis.
double hull_distance(const Cone& k, const Eigen::Vector3d& p);

/// The per-primitive migration vector of ALGORITHM.md: with p the foot on the primitive's axis
/// of the surface normal through v and r the radius there,
/// m_g(v) = r (v - p) / |v - p|^2. Zero when v is on the axis, and for a cone when the foot
/// falls outside [0, L].
Eigen::Vector3d migration_vector(const MedialAtom& sphere, const Eigen::Vector3d& v);
Eigen::Vector3d migration_vector(const Cone& cone, const Eigen::Vector3d& v);

/// A primitive: index < number of atoms is a sphere, otherwise a cone.
using PrimitiveId = int;

/// G with its spatial queries. Immutable after construction; queries are thread-safe.
class TargetShape {
 public:
  /// @param atoms  the spheres (any frame: G lives in the atoms' frame)
  /// @param pairs  the cones (from cone_pairs())
  TargetShape(const MedialSurface& atoms, const std::vector<std::array<int, 2>>& pairs);
  ~TargetShape();
  TargetShape(TargetShape&&) noexcept;
  TargetShape& operator=(TargetShape&&) noexcept;

  std::size_t sphere_count() const { return spheres_.size(); }
  std::size_t cone_count() const { return cones_.size(); }
  const MedialAtom& sphere(PrimitiveId i) const { return spheres_[i]; }
  const Cone& cone(PrimitiveId i) const { return cones_[i - spheres_.size()]; }
  bool is_sphere(PrimitiveId i) const { return i < static_cast<int>(spheres_.size()); }

  /// m_g of primitive i at v.
  Eigen::Vector3d migration_vector(PrimitiveId i, const Eigen::Vector3d& v) const;

  /// Whether p lies in the union (closed primitives).
  bool contains(const Eigen::Vector3d& p) const;

  /// Whether p lies strictly deeper than `eps` inside primitive i (model units; a negative eps
  /// grows the primitive).
  bool primitive_contains(PrimitiveId i, const Eigen::Vector3d& p, double eps = 0) const;

  /// From a point outside the union: the smallest t in [0, t_max] at which the ray
  /// origin + t dir enters a primitive. False if it enters none by t_max.
  /// @param dir need not be unit; t is in units of |dir|
  bool first_entry(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_max,
                   double& t) const;

  /// From a point inside the union: the end of the merged run of primitive intervals along the
  /// ray that contains t = 0 (where the ray leaves the union). False if it lies beyond t_max.
  bool run_end(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_max,
               double& t) const;

  /// Where the line v + t dir meets G next to v, in one pass over the primitives crossed by
  /// t in [-t_max, t_max]: if v is outside the union, the first entry at t > 0 (`inside` =
  /// false); if inside, where the line leaves the union toward negative t, returned as a
  /// negative t (`inside` = true). False if that point lies beyond t_max from v.
  bool line_to_boundary(const Eigen::Vector3d& v, const Eigen::Vector3d& dir, double t_max,
                        double& t, bool& inside) const;

  /// Parameter interval [t0, t1] of the line origin + t dir inside primitive i; false if the
  /// line misses it.
  bool ray_interval(PrimitiveId i, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                    double& t0, double& t1) const;

  /// A closest point of G to p. Exact when p is outside the union. Inside, the nearest of the
  /// exposed (on no other primitive's inside) candidates: each nearby primitive's nearest
  /// surface point, the nearest point of each circle where two nearby spheres meet, and the
  /// exits along 26 directions. Exact for unions of spheres and wherever the nearest point of G
  /// lies inside one primitive's patch; elsewhere (a crease with a cone) an upper bound: every
  /// candidate lies on G.
  Eigen::Vector3d closest_point(const Eigen::Vector3d& p) const;

  /// Distance from p to G (unsigned), with the same exactness as closest_point().
  double distance(const Eigen::Vector3d& p) const { return (closest_point(p) - p).norm(); }

  /// Whether the union comes within `tol` of p (p inside it, or at most tol outside): exact
  /// for spheres and cones. Stops at the first primitive that does.
  bool within(const Eigen::Vector3d& p, double tol) const;

  /// Points of G, uniform in area: `count` points spread over the primitives' surfaces in
  /// proportion to their areas (sphere: 4 pi r^2, cone: its lateral area), each uniform on its
  /// primitive, of which those inside no other primitive are kept (so fewer than `count` come
  /// back). Sample k depends only on (seed, k): reproducible at any thread count.
  std::vector<Eigen::Vector3d> sample_boundary(std::size_t count, std::uint64_t seed) const;

  /// Primitives whose solid meets the axis-aligned box [lo, hi] (exact for spheres; for a cone,
  /// its frustum's bounding box must overlap and the convex hull of its two balls meet the
  /// box), appended in increasing id order.
  void primitives_meeting_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                              std::vector<PrimitiveId>& out) const;

  /// The cones with atom `a` as an end: ids [first, second).
  std::pair<const PrimitiveId*, const PrimitiveId*> cones_of_atom(int a) const {
    return {cones_by_atom_.data() + cones_by_atom_start_[a], cones_by_atom_.data() + cones_by_atom_start_[a + 1]};
  }

 private:
  struct Bvh;
  std::vector<MedialAtom> spheres_;
  std::vector<Cone> cones_;
  std::vector<int> cones_by_atom_start_, cones_by_atom_;  // CSR: atom -> its cones' ids
  std::unique_ptr<Bvh> bvh_;
};

}  // namespace mg
