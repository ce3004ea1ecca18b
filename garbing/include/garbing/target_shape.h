#pragma once
/// \file target_shape.h
/// The target shape G of the garbing (docs/algorithm.md, "Step 3"): the boundary of the union
/// of the primitives (primitives.h, slab.h): every atom's ball, plus for chosen pairs of atoms
/// the cone tangent to both (cone and balls together form the pair's convex hull), plus for a
/// medial mesh's faces the slab of their three atoms (the envelope, docs/algorithm.md "Medial
/// meshes").
/// G is built once, from the atoms and the cone options, and passed as a value to every stage
/// that reads it: the octree, M2's migration and repair, `evaluate atoms`. Queries are exact for
/// balls and cones; a bounding-volume hierarchy over the primitives' boxes is the broad phase.

#include "core/medial_surface.h"
#include "garbing/frame.h"
#include "garbing/primitives.h"
#include "garbing/slab.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mg::garbing {

/// Which pairs of atoms get a cone.
enum class ConeSource {
  regular_triangulation,  ///< pairs adjacent in the regular triangulation (weights r^2)
  all_pairs,              ///< every intersecting pair (the paper; quadratic on pole skeletons)
  ma_edges,               ///< the `.ma` file's edges
  none                    ///< balls only
};

/// Which cones G has.
struct ConeOptions {
  ConeSource source = ConeSource::regular_triangulation;
  /// Keep a cone only if the two spheres' intersection circle has a radius of at least this
  /// fraction of the smaller sphere's radius (0 keeps every intersecting pair; 1 keeps none
  /// but concentric spheres). Cones of barely intersecting balls bridge concavities: chords
  /// across the 60 x 20 torus's hole take H(G, O) from 0.30% (neighbour cones only) to 1.09%
  /// with every regular-triangulation cone. Default 0.9, chosen by measuring H(G, O) over the
  /// reference models (results/cone_filter.md).
  double min_circle_ratio = 0.9;
  /// Keep a cone only if its lateral surface stands off the crease of its two spheres (the
  /// circle where they meet) by at most this many rc / 8 (the automatic leaf side bound;
  /// rc = (rmin + rmax) / 2, from the atoms alone); 0: no limit. Deep crease fills are where
  /// G strays from the object most. Default 1, chosen with the circle ratio by measuring
  /// H(G, O) (results/cone_filter.md).
  double max_collar = 1;
};

/// Parses "rt", "all", "edges" or "none". @throws InvalidInput
ConeSource parse_cone_source(const std::string& name);

/// Checks that every radius is > 0, as G of the atoms alone needs (a ball of radius 0 is a
/// point; only a medial mesh's hulls give it a volume).
/// @throws InvalidInput naming the first atom of radius 0 (its index in `atoms`)
void require_positive_radii(const MedialSurface& atoms);

/// The pairs (i < j) that get a cone: from `opt.source`, kept when the two balls intersect,
/// neither contains the other, and the circle-ratio and collar filters pass. Sorted. Chosen
/// on the atoms as given (world coordinates).
/// @pre atoms valid, radii > 0; 0 <= min_circle_ratio <= 1; max_collar >= 0
/// @throws InvalidInput
std::vector<std::array<int, 2>> cone_pairs(const MedialSurface& atoms, const ConeOptions& opt);

/// Which primitives G has.
enum class PrimitiveSet {
  automatic,  ///< envelope when the atoms have edges or faces, else atoms
  /// "ma": the envelope of a medial mesh: every atom's ball, one cone per edge (the faces'
  /// edges included, whether or not the balls intersect) and one slab per face.
  envelope,
  /// "rt": the atoms' balls and the cones ConeOptions chooses (the paper's path; edges and
  /// faces ignored).
  atoms
};

/// Parses "auto", "ma" or "rt". @throws InvalidInput
PrimitiveSet parse_primitive_set(const std::string& name);

/// automatic resolved for these atoms: envelope when they have edges or faces, else atoms.
PrimitiveSet resolve(PrimitiveSet set, const MedialSurface& atoms);

/// How a medial mesh's edges and faces became primitives (envelope_primitives()).
struct EnvelopeCounts {
  long edges = 0;            ///< distinct edges, the faces' edges included
  long repeated_edges = 0;   ///< edge lines or face sides repeating one (either way round)
  long edges_in_a_ball = 0;  ///< one ball holds the other: the edge's hull is that ball, no cone
  long faces = 0;            ///< distinct faces (as sets of three atoms)
  long repeated_faces = 0;   ///< face lines repeating one
  long collinear_faces = 0;  ///< centres collinear: the edge hulls cover the face, no slab
  long slabs_without_tangent_triangles = 0;  ///< radii too steep for a plane touching all three
};

/// The envelope's hulls: cones (i < j, sorted) and slabs (i < j < k, sorted) of a medial mesh.
struct EnvelopePrimitives {
  std::vector<std::array<int, 2>> cones;
  std::vector<std::array<int, 3>> slabs;
  EnvelopeCounts counts;
};

/// The cones and slabs of the envelope of `atoms` (chosen on the atoms as given): every distinct
/// edge, and every side of every face, whose balls neither holds the other, is a cone; every
/// distinct face with non-collinear centres is a slab. @pre atoms valid
EnvelopePrimitives envelope_primitives(const MedialSurface& atoms);

/// A primitive of G: id < sphere_count() is the ball of atom id; the next cone_count() ids are
/// the cones (cone id - sphere_count()), then the slabs.
///
/// Each primitive has its own *piece* of G, which the union queries below test: a ball's piece
/// is the ball, a cone's its solid, a slab's its prism (slab.h): the rest of a slab's solid is
/// its balls and edge hulls, primitives of G themselves, so the union of the pieces is G's. A
/// slab without tangent triangles has no piece. m_g is the slab's own (slab.h).
using PrimitiveId = int;

/// G with its spatial queries, in the coordinates of its frame (every point given to or
/// returned by a query is local). Immutable after construction; queries are thread-safe.
class TargetShape {
 public:
  /// G of the atoms' balls and the cones of `pairs`, expressed in `frame` (atom centres
  /// mapped by frame.to_local; world coordinates by default). G keeps the atoms' balls: pass
  /// them with std::move when the caller no longer needs them (no copy; their connectivity is
  /// dropped). Then neither `pairs` nor another argument may refer into the moved surface (its
  /// edges, say), and nothing computed from it may sit in the same call: the parameter may be
  /// moved into before the other arguments are evaluated (compute the frame first, as garb()).
  /// @pre atoms valid; every pair indexes two intersecting atoms, neither holding the other
  TargetShape(MedialSurface atoms, const std::vector<std::array<int, 2>>& pairs,
              const Frame& frame = {});
  /// G of a medial mesh's envelope (is_envelope()): the atoms' balls, the cones of `pairs` and
  /// the slabs of `triples`; `counts` are kept for reports. @pre atoms valid; each pair's balls
  /// neither holding the other; each triple's centres not collinear (envelope_primitives()
  /// chooses them so)
  TargetShape(MedialSurface atoms, const std::vector<std::array<int, 2>>& pairs,
              const std::vector<std::array<int, 3>>& triples, const Frame& frame,
              const EnvelopeCounts& counts = {});
  ~TargetShape();
  TargetShape(TargetShape&&) noexcept;
  TargetShape& operator=(TargetShape&&) noexcept;

  const Frame& frame() const { return frame_; }
  /// The balls of G (the atoms, in G's frame), without connectivity.
  const MedialSurface& atoms() const { return atoms_; }
  std::size_t sphere_count() const { return atoms_.atoms.size(); }
  std::size_t cone_count() const { return cones_.size(); }
  std::size_t slab_count() const { return slabs_.size(); }
  std::size_t primitive_count() const {
    return atoms_.atoms.size() + cones_.size() + slabs_.size();
  }
  const MedialAtom& sphere(PrimitiveId i) const { return atoms_.atoms[i]; }
  /// Cone i, restored from what G stores of it (primitives.h, StoredCone): a value, bit for
  /// bit make_cone of its two atoms (in G's frame).
  Cone cone(PrimitiveId i) const { return restored(cones_[i - atoms_.atoms.size()]); }
  /// What G stores of cone i (its atoms, axis, radii: read without restoring the cone).
  const StoredCone& stored_cone(PrimitiveId i) const { return cones_[i - atoms_.atoms.size()]; }
  /// The two atoms of cone i (a, b as its pair gave them), without restoring it.
  std::array<int, 2> cone_atoms(PrimitiveId i) const {
    const StoredCone& k = cones_[i - atoms_.atoms.size()];
    return {k.a, k.b};
  }
  const Slab& slab(PrimitiveId i) const { return slabs_[i - first_slab_]; }
  bool is_sphere(PrimitiveId i) const { return i < static_cast<int>(atoms_.atoms.size()); }
  bool is_cone(PrimitiveId i) const { return !is_sphere(i) && i < first_slab_; }
  bool is_slab(PrimitiveId i) const { return i >= first_slab_; }
  /// The id of slab k (0-based among the slabs).
  PrimitiveId slab_id(int k) const { return first_slab_ + k; }
  /// How the medial mesh's edges and faces became primitives (zeros for PrimitiveSet::atoms).
  const EnvelopeCounts& envelope_counts() const { return counts_; }
  /// Whether G is a medial mesh's envelope (the constructor with slabs), not the paper's G of
  /// the atoms: the octree then reads its cones and slabs as the envelope's (octree.h).
  bool is_envelope() const { return envelope_; }

  /// The cones with atom `a` as an end, as primitive ids [first, second), increasing.
  std::pair<const PrimitiveId*, const PrimitiveId*> cones_of_atom(int a) const {
    return {cones_by_atom_.data() + cones_by_atom_start_[a],
            cones_by_atom_.data() + cones_by_atom_start_[a + 1]};
  }

  /// The slabs with atom `a` as a corner, as primitive ids [first, second), increasing.
  std::pair<const PrimitiveId*, const PrimitiveId*> slabs_of_atom(int a) const {
    return {slabs_by_atom_.data() + slabs_by_atom_start_[a],
            slabs_by_atom_.data() + slabs_by_atom_start_[a + 1]};
  }

  /// m_g of primitive i at v.
  Eigen::Vector3d migration_vector(PrimitiveId i, const Eigen::Vector3d& v) const;

  /// Whether p lies in the union (closed primitives).
  bool contains(const Eigen::Vector3d& p) const;

  /// Whether p lies strictly deeper than `eps` inside primitive i's piece (model units; a
  /// negative eps grows it).
  bool primitive_contains(PrimitiveId i, const Eigen::Vector3d& p, double eps = 0) const;

  /// Parameter interval [t0, t1] of the line origin + t dir inside primitive i's piece; false
  /// if the line misses it.
  bool ray_interval(PrimitiveId i, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                    double& t0, double& t1) const;

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

  /// A closest point of G to p. Exact when p is outside the union. Inside, the nearest of the
  /// exposed (on no other primitive's inside) candidates: each nearby primitive's nearest
  /// surface point, the nearest point of each crease where two nearby spheres meet, and the
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

  /// Primitives whose piece meets the axis-aligned box [lo, hi] (exact for spheres and slabs'
  /// prisms; for a cone, its frustum's bounding box must overlap and the convex hull of its two
  /// balls meet the box), appended in increasing id order.
  void primitives_meeting_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                              std::vector<PrimitiveId>& out) const;

 private:
  struct Bvh;
  Frame frame_;
  MedialSurface atoms_;                                   // the balls, in frame_ (no connectivity)
  std::vector<StoredCone> cones_;                         // in frame_
  std::vector<int> cones_by_atom_start_, cones_by_atom_;  // CSR: atom -> its cones' ids
  std::vector<Slab> slabs_;                               // in frame_
  int first_slab_ = 0;                                    // sphere_count + cone_count
  std::vector<int> slabs_by_atom_start_, slabs_by_atom_;  // CSR: atom -> its slabs' ids
  EnvelopeCounts counts_;
  bool envelope_ = true;
  std::unique_ptr<Bvh> bvh_;
};

/// G of the atoms: the cones cone_pairs(atoms, cones) chooses (on the atoms as given), the
/// primitives expressed in `frame` (the garbing passes bounding_cube_frame(atoms); the default,
/// world coordinates, is what `evaluate atoms` measures in).
/// Taken by value, as TargetShape's constructors: std::move them in when no longer needed.
/// @pre atoms valid; cone options as cone_pairs   @throws InvalidInput
TargetShape make_target_shape(MedialSurface atoms, const ConeOptions& cones = {},
                              const Frame& frame = {});

/// G of the primitive set: for the envelope, envelope_primitives(atoms) (`cones` unused); for
/// atoms, as above. @throws InvalidInput
TargetShape make_target_shape(MedialSurface atoms, PrimitiveSet primitives,
                              const ConeOptions& cones, const Frame& frame = {});

}  // namespace mg::garbing
