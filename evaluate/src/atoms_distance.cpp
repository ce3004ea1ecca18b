#include "evaluate/atoms_distance.h"

#include "core/errors.h"
#include "evaluate/mesh_distance.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace mg::evaluate {

AtomsDistance atoms_distance(const PolygonSoup& mesh, const MedialSurface& atoms,
                             const AtomsDistanceOptions& opt, const std::string& name) {
  validate(atoms);
  AtomsDistance r =
      atoms_distance(mesh, garbing::make_target_shape(atoms, opt.primitives, opt.cones), opt, name);
  r.envelope = garbing::resolve(opt.primitives, atoms) == garbing::PrimitiveSet::envelope;
  return r;
}

AtomsDistance atoms_distance(const PolygonSoup& mesh, const garbing::TargetShape& shape,
                             const AtomsDistanceOptions& opt, const std::string& name) {
  if (!shape.frame().is_world())
    throw InvalidInput("atoms_distance: G must be in world coordinates");
  const TriangleIndex index(mesh, name);
  AtomsDistance r;
  r.cones = shape.cone_count();
  r.slabs = shape.slab_count();
  r.diagonal = bbox_diagonal(mesh.points);
  if (!(r.diagonal > 0)) throw InvalidInput(name + ": bounding-box diagonal is 0");
  std::size_t referenced = 0;
  {
    std::vector<char> used(mesh.points.size(), 0);
    for (const auto& f : mesh.faces)
      for (int v : f) used[v] = 1;
    referenced = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
  }
  SamplingOptions sampling;
  sampling.count = opt.samples > 0 ? opt.samples : std::max<std::size_t>(100000, 10 * referenced);
  sampling.seed = opt.seed;
  const SurfaceSamples on_mesh = sample_surface(mesh, sampling, name);
  // Samples of G: area-uniform points of the primitives kept when on no other primitive's
  // inside (unbiased, weight 1: they make the mean and RMS). On pole skeletons most of the
  // primitives' area is buried (measured: 0.2% kept on the bumpy torus atoms), so the nearest
  // points of G to up to 20,000 of the mesh's samples are added with weight 0: exact points of
  // G that sharpen the maximum where the mesh is.
  SurfaceSamples on_g;
  on_g.points = shape.sample_boundary(sampling.count, opt.seed);
  on_g.weights.assign(on_g.points.size(), 1.0);
  const std::size_t stride = std::max<std::size_t>(1, on_mesh.points.size() / 20000);
  std::vector<Eigen::Vector3d> projected((on_mesh.points.size() + stride - 1) / stride);
  tbb::parallel_for(std::size_t(0), projected.size(), [&](std::size_t k) {
    projected[k] = shape.closest_point(on_mesh.points[k * stride]);
  });
  r.g_unbiased = on_g.points.size();
  on_g.points.insert(on_g.points.end(), projected.begin(), projected.end());
  on_g.weights.resize(on_g.points.size(), 0.0);
  if (r.g_unbiased == 0) on_g.weights.assign(on_g.points.size(), 1.0);
  const DistanceOracle to_g = [&shape](const Eigen::Vector3d* p, std::size_t n, double* d) {
    for (std::size_t i = 0; i < n; ++i) d[i] = shape.distance(p[i]);
  };
  r.distance = two_sided_distance(on_mesh, to_g, on_g, index.oracle());
  r.mesh_samples = on_mesh.points.size();
  r.g_samples = on_g.points.size();
  return r;
}

}  // namespace mg::evaluate
