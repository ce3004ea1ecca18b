// The OpenVDB translation unit: spheres to a narrow-band level set, level set to a mesh.
#include "evaluate/vdb_mesh.h"

#include "core/errors.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

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
  validate(atoms);
  const double diagonal = spheres_bbox_diagonal(atoms);
  if (!(opt.voxel >= 0) || !std::isfinite(opt.voxel)) {
    std::ostringstream m;
    m << "--voxel must be >= 0 (0 = diagonal / 400), got " << opt.voxel;
    throw InvalidInput(m.str());
  }
  if (!(opt.half_width >= 1)) throw InvalidInput("narrow-band half-width must be >= 1 voxel");
  VdbMesh r;
  r.voxel = opt.voxel > 0 ? opt.voxel : diagonal / 400;
  if (diagonal / r.voxel > 1e9) {
    std::ostringstream m;
    m << "--voxel " << r.voxel << " is too small for a bounding-box diagonal of " << diagonal;
    throw InvalidInput(m.str());
  }
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

  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, triangles, quads, /*isovalue=*/0.0,
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
  return r;
}

}  // namespace mg::evaluate
