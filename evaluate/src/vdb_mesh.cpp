// The OpenVDB translation unit: spheres, or G's sampled signed distance, to a narrow-band level
// set; level set to a mesh.
#include "evaluate/vdb_mesh.h"

#include "core/errors.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <utility>
#include <vector>

namespace mg::evaluate {
namespace {

/// OpenVDB's minimum radius, voxels: smaller spheres are skipped (ParticlesToLevelSet's default).
constexpr double kMinRadiusVoxels = 1.5;

/// The particle list ParticlesToLevelSet reads: the kept spheres, by reference.
class SphereList {
 public:
  using PosType = openvdb::Vec3R;
  explicit SphereList(const std::vector<MedialAtom>& atoms) : atoms_(atoms) {}
  std::size_t size() const { return atoms_.size(); }
  void getPos(std::size_t n, openvdb::Vec3R& p) const {
    const Eigen::Vector3d& c = atoms_[n].centre;
    p = openvdb::Vec3R(c.x(), c.y(), c.z());
  }
  void getPosRad(std::size_t n, openvdb::Vec3R& p, openvdb::Real& r) const {
    getPos(n, p);
    r = atoms_[n].radius;
  }

 private:
  const std::vector<MedialAtom>& atoms_;
};

void initialise_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

/// The zero level of `grid` as r.mesh (and r.quads): quads split along their shorter diagonal,
/// faces turned outward. @throws InvalidInput when the mesh is empty
void mesh_zero_level(const openvdb::FloatGrid& grid, VdbMesh& r) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, /*isovalue=*/0.0,
                               /*adaptivity=*/0.0);
  r.quads = quads.size();
  r.mesh.points.reserve(points.size());
  for (const auto& p : points) r.mesh.points.emplace_back(p.x(), p.y(), p.z());
  r.mesh.faces.reserve(triangles.size() + 2 * quads.size());
  auto idx = [](openvdb::Index32 i) { return static_cast<int>(i); };
  for (const auto& t : triangles) r.mesh.faces.push_back({idx(t[2]), idx(t[1]), idx(t[0])});
  for (const auto& q : quads) {
    const int a = idx(q[3]), b = idx(q[2]), c = idx(q[1]), d = idx(q[0]);  // turned outward
    const auto& P = r.mesh.points;
    if ((P[a] - P[c]).squaredNorm() <= (P[b] - P[d]).squaredNorm()) {
      r.mesh.faces.push_back({a, b, c});
      r.mesh.faces.push_back({a, c, d});
    } else {
      r.mesh.faces.push_back({a, b, d});
      r.mesh.faces.push_back({b, c, d});
    }
  }
  if (r.mesh.faces.empty())
    throw InvalidInput("OpenVDB produced an empty mesh (voxel " + std::to_string(r.voxel) + ")");
}

/// The checks both paths share; returns the voxel (0 = diagonal / 400). @throws InvalidInput
double checked_voxel(const VdbOptions& opt, double diagonal) {
  if (!(opt.voxel >= 0) || !std::isfinite(opt.voxel)) {
    std::ostringstream m;
    m << "--voxel must be >= 0 (0 = diagonal / 400), got " << opt.voxel;
    throw InvalidInput(m.str());
  }
  if (!(opt.half_width >= 1)) throw InvalidInput("narrow-band half-width must be >= 1 voxel");
  const double voxel = opt.voxel > 0 ? opt.voxel : diagonal / 400;
  if (diagonal / voxel > 1e9) {
    std::ostringstream m;
    m << "--voxel " << voxel << " is too small for a bounding-box diagonal of " << diagonal;
    throw InvalidInput(m.str());
  }
  return voxel;
}

using FloatLeaf = openvdb::FloatTree::LeafNodeType;
using LeafList = std::vector<std::unique_ptr<FloatLeaf>>;

/// G's signed distance in the narrow band: blocks of 8^3 leaves (64^3 voxels) near G, then
/// their leaves near G, then the voxels. A block or leaf is skipped when no primitive comes
/// within the band of its voxels (outside) or one holds it deeper than the band (inside);
/// signedFloodFill gives both their sign.
class EnvelopeSampler {
 public:
  EnvelopeSampler(const garbing::TargetShape& g, double voxel, double band)
      : g_(g), voxel_(voxel), band_(band) {
    bounds_.reserve(g.primitive_count());
    for (std::size_t i = 0; i < g.primitive_count(); ++i)
      bounds_.push_back(solid_bound(static_cast<garbing::PrimitiveId>(i)));
    // Slabs are evaluated only where their stationary point may lie in their triangle
    // (foot_may_be_inside): elsewhere their distance is their edge hulls', which are cones (or
    // balls holding the other end) of G.
  }

  /// The leaves with a voxel in the band, in a fixed order (blocks, then leaves, by x, y, z).
  LeafList sample() const {
    Eigen::AlignedBox3d all;
    for (const auto& b : bounds_) all.extend(b.box);
    std::array<std::int64_t, 3> first{}, count{};
    for (int a = 0; a < 3; ++a) {
      const double lo = std::floor((all.min()[a] - band_) / voxel_);
      const double hi = std::ceil((all.max()[a] + band_) / voxel_);
      if (!(std::abs(lo) < 1 << 30) || !(std::abs(hi) < 1 << 30))
        throw InvalidInput("voxel " + std::to_string(voxel_) +
                           ": the grid would pass 2^30 voxels from the origin");
      first[a] = floor_to(static_cast<std::int64_t>(lo), kBlock);
      count[a] = (static_cast<std::int64_t>(hi) - first[a]) / kBlock + 1;
    }
    std::vector<openvdb::Coord> blocks;
    for (std::int64_t i = 0; i < count[0]; ++i)
      for (std::int64_t j = 0; j < count[1]; ++j)
        for (std::int64_t k = 0; k < count[2]; ++k)
          blocks.emplace_back(static_cast<int>(first[0] + i * kBlock),
                              static_cast<int>(first[1] + j * kBlock),
                              static_cast<int>(first[2] + k * kBlock));
    std::vector<LeafList> per_block(blocks.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 1), [&](const auto& range) {
      for (std::size_t b = range.begin(); b != range.end(); ++b)
        per_block[b] = sample_block(blocks[b]);
    });
    LeafList leaves;
    for (auto& list : per_block)
      for (auto& leaf : list) leaves.push_back(std::move(leaf));
    return leaves;
  }

 private:
  static constexpr int kLeaf = FloatLeaf::DIM;  // voxels per leaf side
  static constexpr int kBlock = kLeaf * 8;      // voxels per block side
  static constexpr int kLeafVoxels = kLeaf * kLeaf * kLeaf;

  static std::int64_t floor_to(std::int64_t v, std::int64_t step) {
    return (v >= 0 ? v / step : -((-v + step - 1) / step)) * step;
  }

  /// A box and a ball holding a primitive's solid: cheap lower bounds of its distance.
  struct Bound {
    Eigen::AlignedBox3d box;
    Eigen::Vector3d centre;
    double radius = 0;
    double distance(const Eigen::Vector3d& p) const {
      return std::max(box.exteriorDistance(p), (p - centre).norm() - radius);
    }
  };

  /// A cone's or slab's solid is the hull of its balls: it lies in their boxes, and in the ball
  /// about their centres' mean reaching every one of them.
  Bound solid_bound(garbing::PrimitiveId i) const {
    std::vector<MedialAtom> balls;
    if (g_.is_sphere(i)) {
      balls = {g_.sphere(i)};
    } else if (g_.is_cone(i)) {
      balls = {g_.atoms().atoms[g_.cone_atoms(i)[0]], g_.atoms().atoms[g_.cone_atoms(i)[1]]};
    } else {
      const garbing::Slab& k = g_.slab(i);
      for (int a = 0; a < 3; ++a) balls.push_back({k.c[a], k.r[a]});
    }
    Bound b;
    b.centre = Eigen::Vector3d::Zero();
    for (const MedialAtom& a : balls) {
      b.box.extend(garbing::bounding_box(a));
      b.centre += a.centre / static_cast<double>(balls.size());
    }
    for (const MedialAtom& a : balls)
      b.radius = std::max(b.radius, (a.centre - b.centre).norm() + a.radius);
    return b;
  }

  /// Primitive i's signed distance at p: exact outside it; inside, minus at most the depth.
  double signed_distance(garbing::PrimitiveId i, const Eigen::Vector3d& p) const {
    if (g_.is_sphere(i)) return (p - g_.sphere(i).centre).norm() - g_.sphere(i).radius;
    if (g_.is_cone(i)) return garbing::hull_distance(g_.cone(i), p);
    return garbing::slab_distance(g_.slab(i), p);
  }

  Eigen::Vector3d position(const openvdb::Coord& c) const {
    return voxel_ * Eigen::Vector3d(c.x(), c.y(), c.z());
  }

  /// The box of the voxel centres of the cube of `side` voxels at `origin`, grown by `grow`
  /// (model units).
  Eigen::AlignedBox3d grown_box(const openvdb::Coord& origin, int side, double grow) const {
    const Eigen::Vector3d lo = position(origin);
    const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(voxel_ * (side - 1));
    return {lo - Eigen::Vector3d::Constant(grow), hi + Eigen::Vector3d::Constant(grow)};
  }

  /// (lower bound of its distance over the voxel centres of the cube, id) of each primitive of
  /// `parent` that may come within the band of one of them, by id.
  std::vector<std::pair<double, int>> near_cube(const openvdb::Coord& origin, int side,
                                                const std::vector<int>& parent) const {
    const Eigen::AlignedBox3d box = grown_box(origin, side, 0);
    const Eigen::Vector3d centre = box.center();
    const double half_diagonal = box.diagonal().norm() / 2;
    std::vector<std::pair<double, int>> near;
    for (int i : parent) {
      const Bound& b = bounds_[i];
      const double bound = std::max(std::sqrt(box.squaredExteriorDistance(b.box)),
                                    (centre - b.centre).norm() - b.radius - half_diagonal);
      if (bound < band_) near.emplace_back(std::max(bound, 0.0), i);
    }
    return near;
  }

  /// Whether a primitive holds every voxel centre of the cube deeper than the band.
  bool deep_inside(const openvdb::Coord& origin, int side,
                   const std::vector<std::pair<double, int>>& near) const {
    const double half = voxel_ * (side - 1) / 2;
    const Eigen::Vector3d centre = position(origin) + Eigen::Vector3d::Constant(half);
    const double depth = half * std::sqrt(3.0) + band_;
    return std::any_of(near.begin(), near.end(), [&](const std::pair<double, int>& c) {
      return c.first == 0 && g_.primitive_contains(c.second, centre, depth);
    });
  }

  /// The leaves of a block of kBlock voxels at `origin`, x, y, z order of octants recursively.
  LeafList sample_block(const openvdb::Coord& origin) const {
    const Eigen::AlignedBox3d box = grown_box(origin, kBlock, band_);
    std::vector<int> candidates;
    g_.primitives_meeting_box(box.min(), box.max(), candidates);
    // A ball lies in each of its cones: where one of them is a candidate too, the union and the
    // distance outside it are the cone's (the depth inside stays a bound). A cone is found by
    // its frustum's box, which leaves its balls' caps out: a block reached only by a cap keeps
    // the ball.
    std::vector<int> cone_atoms;
    for (int i : candidates)
      if (g_.is_cone(i)) {
        cone_atoms.push_back(g_.cone_atoms(i)[0]);
        cone_atoms.push_back(g_.cone_atoms(i)[1]);
      }
    std::sort(cone_atoms.begin(), cone_atoms.end());
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](int i) {
                                      return g_.is_sphere(i) &&
                                             std::binary_search(cone_atoms.begin(),
                                                                cone_atoms.end(), i);
                                    }),
                     candidates.end());
    LeafList leaves;
    sample_cube(origin, kBlock, candidates, leaves);
    return leaves;
  }

  /// Appends the leaves of the cube of `side` voxels (kLeaf times a power of 2) at `origin` that
  /// have a voxel in the band, from the primitives of `parent` (by id), in the order of its
  /// octants (x, y, z), recursively: the same order at any thread count.
  void sample_cube(const openvdb::Coord& origin, int side, const std::vector<int>& parent,
                   LeafList& out) const {
    std::vector<std::pair<double, int>> near = near_cube(origin, side, parent);
    if (near.empty() || deep_inside(origin, side, near)) return;
    if (side == kLeaf) {
      if (auto leaf = sample_leaf(origin, near)) out.push_back(std::move(leaf));
      return;
    }
    std::vector<int> ids;
    ids.reserve(near.size());
    for (const auto& c : near) ids.push_back(c.second);
    const int half = side / 2;
    std::array<LeafList, 8> octants;
    auto octant = [&](int k) {
      const openvdb::Coord o =
          origin + openvdb::Coord(half * (k >> 2), half * (k >> 1 & 1), half * (k & 1));
      sample_cube(o, half, ids, octants[k]);
    };
    if (half > kLeaf)
      tbb::parallel_for(0, 8, octant);
    else
      for (int k = 0; k < 8; ++k) octant(k);
    for (auto& leaves : octants)
      for (auto& leaf : leaves) out.push_back(std::move(leaf));
  }

  /// False when the slab's stationary point for p (docs/algorithm.md, "The slab") lies outside
  /// its triangle by more than 1e-9 in barycentric coordinates, or does not exist: then
  /// slab_distance(p) is the least of its edge hulls' distances.
  static bool foot_may_be_inside(const garbing::Slab& k, const Eigen::Vector3d& p) {
    if (!k.has_tangent_triangles) return false;
    const double h = k.normal.dot(p - k.c[0]);
    const double root = std::sqrt(std::max(0.0, 1 - k.gradient.squaredNorm()));
    const Eigen::Vector3d w = p - h * k.normal + (std::abs(h) / root) * k.gradient - k.c[0];
    const Eigen::Vector3d e1 = k.c[1] - k.c[0], e2 = k.c[2] - k.c[0];
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double b1 = w.dot(e1), b2 = w.dot(e2), det = d11 * d22 - d12 * d12;
    const double s = (d22 * b1 - d12 * b2) / det, t = (d11 * b2 - d12 * b1) / det;
    constexpr double kTolerance = 1e-9;
    return s >= -kTolerance && t >= -kTolerance && s + t <= 1 + kTolerance;
  }

  /// A primitive's value at a point q and, where known, a (sub)gradient there. Its signed
  /// distance is convex, so it is at least value + gradient . (p - q) at every p; and, being
  /// 1-Lipschitz, at least value - |p - q|.
  struct Tangent {
    double value = 0;
    int id = -1;
    bool has_gradient = false;
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    bool operator<(const Tangent& o) const {
      return value < o.value || (value == o.value && id < o.id);
    }
  };

  Tangent tangent(garbing::PrimitiveId i, const Eigen::Vector3d& q) const {
    Tangent t;
    t.id = i;
    if (g_.is_slab(i)) {  // outside: the distance to a convex solid, and its gradient
      const garbing::Slab& k = g_.slab(i);
      const Eigen::Vector3d v = q - garbing::closest_solid_point(k, q);
      t.has_gradient = v.norm() > 0;
      t.value = t.has_gradient ? v.norm() : garbing::slab_distance(k, q);
      if (t.has_gradient) t.gradient = v / v.norm();
      return t;
    }
    // A ball, or a cone's nearest interpolated ball (the minimiser over t: Danskin).
    Eigen::Vector3d v;
    if (g_.is_sphere(i)) {
      v = q - g_.sphere(i).centre;
      t.value = v.norm() - g_.sphere(i).radius;
    } else {
      const garbing::Cone k = g_.cone(i);
      const double along = garbing::hull_parameter(k, q);
      v = q - (k.c1 + (along * k.length) * k.u);  // as hull_distance computes it
      t.value = v.norm() - (k.r1 + along * (k.r2 - k.r1));
    }
    t.has_gradient = v.norm() > 0;
    if (t.has_gradient) t.gradient = v / v.norm();
    return t;
  }

  /// The leaf's voxels: active inside the band, -/+ band outside it; null when none is active.
  /// Per octant of 4^3 voxels, the primitives' tangents at its centre order and bound them, so
  /// that a voxel evaluates exactly only the few that can be nearest.
  /// @param near  the primitives that may come within the band of a voxel of the leaf
  std::unique_ptr<FloatLeaf> sample_leaf(const openvdb::Coord& origin,
                                         const std::vector<std::pair<double, int>>& near) const {
    constexpr int kHalf = kLeaf / 2;
    const double reach = voxel_ * (kHalf - 1) * std::sqrt(3.0) / 2;  // octant centre to corner
    const double margin = 1e-6 * voxel_;                             // rounding of the bounds
    auto leaf = std::make_unique<FloatLeaf>(origin, static_cast<float>(band_), false);
    bool any_active = false;
    // Those that come within the band of a voxel by the value at the leaf's centre.
    const double leaf_reach = voxel_ * (kLeaf - 1) * std::sqrt(3.0) / 2;
    const Eigen::Vector3d centre =
        position(origin) + Eigen::Vector3d::Constant(voxel_ * (kLeaf - 1) / 2);
    std::vector<int> ids;
    for (const auto& c : near)
      if (signed_distance(c.second, centre) - leaf_reach < band_) ids.push_back(c.second);
    std::vector<Tangent> tangents;
    for (int k = 0; k < 8; ++k) {
      const openvdb::Coord corner(kHalf * (k >> 2), kHalf * (k >> 1 & 1), kHalf * (k & 1));
      const Eigen::Vector3d q =
          position(origin + corner) + Eigen::Vector3d::Constant(voxel_ * (kHalf - 1) / 2);
      tangents.clear();
      for (int i : ids) {
        const Tangent t = tangent(i, q);
        if (t.value - reach < band_) tangents.push_back(t);
      }
      std::sort(tangents.begin(), tangents.end());
      for (int x = 0; x < kHalf; ++x)
        for (int y = 0; y < kHalf; ++y)
          for (int z = 0; z < kHalf; ++z) {
            const openvdb::Coord local = corner + openvdb::Coord(x, y, z);
            const Eigen::Vector3d p = position(origin + local);
            const double reach_p = (p - q).norm();
            double d = band_;
            for (const Tangent& t : tangents) {
              if (t.value - reach_p >= d + margin) break;  // so are the rest: none lowers d
              if (t.has_gradient && t.value + t.gradient.dot(p - q) - margin >= d) continue;
              if (g_.is_slab(t.id) && !foot_may_be_inside(g_.slab(t.id), p)) continue;
              d = std::min(d, signed_distance(t.id, p));
              if (d <= -band_) break;
            }
            const openvdb::Index n = FloatLeaf::coordToOffset(local);
            if (d > -band_ && d < band_) {
              leaf->setValueOn(n, static_cast<float>(d));
              any_active = true;
            } else if (d <= -band_) {
              leaf->setValueOff(n, static_cast<float>(-band_));
            }
          }
    }
    if (!any_active) return nullptr;
    return leaf;
  }

  const garbing::TargetShape& g_;
  double voxel_, band_;
  std::vector<Bound> bounds_;  // per primitive
};

}  // namespace

double spheres_bbox_diagonal(const MedialSurface& atoms) {
  if (atoms.atoms.empty()) return 0;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const MedialAtom& a : atoms.atoms) {
    lo = lo.cwiseMin(a.centre - Eigen::Vector3d::Constant(a.radius));
    hi = hi.cwiseMax(a.centre + Eigen::Vector3d::Constant(a.radius));
  }
  return (hi - lo).norm();
}

VdbMesh vdb_mesh(const MedialSurface& atoms, const VdbOptions& opt) {
  if (garbing::resolve(opt.primitives, atoms) == garbing::PrimitiveSet::envelope)
    return vdb_mesh(garbing::make_target_shape(atoms, garbing::PrimitiveSet::envelope, {}), opt);
  validate(atoms);
  VdbMesh r;
  r.voxel = checked_voxel(opt, spheres_bbox_diagonal(atoms));
  double max_radius = 0;
  for (const MedialAtom& a : atoms.atoms) {
    if (a.radius / r.voxel < kMinRadiusVoxels) ++r.dropped_spheres;
    max_radius = std::max(max_radius, a.radius);
  }
  if (r.dropped_spheres == atoms.atoms.size()) {
    std::ostringstream m;
    m << "every sphere is under " << kMinRadiusVoxels << " voxels (voxel " << r.voxel
      << "): OpenVDB would mesh nothing; use a smaller --voxel";
    throw InvalidInput(m.str());
  }

  initialise_openvdb();
  openvdb::FloatGrid::Ptr grid =
      openvdb::createLevelSet<openvdb::FloatGrid>(r.voxel, static_cast<float>(opt.half_width));
  {
    openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
    raster.setRmin(kMinRadiusVoxels);
    raster.setRmax(max_radius / r.voxel + 1);  // OpenVDB's default (100 voxels) drops big spheres
    raster.rasterizeSpheres(SphereList(atoms.atoms));
    raster.finalize();
  }
  openvdb::tools::pruneLevelSet(grid->tree());
  mesh_zero_level(*grid, r);
  return r;
}

VdbMesh vdb_mesh(const garbing::TargetShape& g, const VdbOptions& opt) {
  if (!g.frame().is_world()) throw InvalidInput("vdb_mesh: G must be in world coordinates");
  VdbMesh r;
  r.voxel = checked_voxel(opt, spheres_bbox_diagonal(g.atoms()));
  r.envelope = true;
  r.cones = g.cone_count();
  r.slabs = g.slab_count();
  const double band = opt.half_width * r.voxel;  // model units

  initialise_openvdb();
  openvdb::FloatGrid::Ptr grid =
      openvdb::createLevelSet<openvdb::FloatGrid>(r.voxel, static_cast<float>(opt.half_width));
  LeafList leaves = EnvelopeSampler(g, r.voxel, band).sample();
  r.leaves = leaves.size();
  for (auto& leaf : leaves) grid->tree().addLeaf(leaf.release());  // in the sampler's order
  openvdb::tools::signedFloodFill(grid->tree());
  openvdb::tools::pruneLevelSet(grid->tree());
  mesh_zero_level(*grid, r);
  return r;
}

}  // namespace mg::evaluate
