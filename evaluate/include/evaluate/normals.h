#pragma once
/// \file normals.h
/// Smoothness against a reference (`evaluate normals`): how far the mesh's facet normals turn
/// away from the reference surface's normal at the closest point. This measures the "bumps"
/// of a union of balls (the paper's Figure 3) that a distance barely sees.

#include "core/mesh.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace mg::evaluate {

struct NormalOptions {
  /// Area-uniform samples on the mesh; 0 = default_sample_count(mesh, reference).
  std::size_t samples = 0;
  std::uint64_t seed = 1;
  /// true: the reference normal is interpolated (barycentric) from angle-weighted vertex
  /// normals, i.e. the smooth surface the reference samples; false: the reference's facet
  /// normal (then a mesh against itself gives exactly 0).
  bool smooth_reference = true;
};

/// Angles between the mesh's facet normal at a sample and the reference normal at the sample's
/// closest point on the reference, in degrees, over area-uniform samples of the mesh (so the
/// mean and the percentile are area-weighted). Both meshes must be oriented the same way
/// (CCW from outside): an inverted face counts as about 180 degrees.
struct NormalDeviation {
  double mean_deg = 0;  ///< area-weighted mean
  double p95_deg = 0;   ///< area-weighted 95th percentile
  double max_deg = 0;
  std::size_t samples = 0;  ///< samples measured
  std::size_t skipped = 0;  ///< samples whose reference normal is undefined (zero vector)
};

/// @param mesh_name, reference_name  used in messages
/// @pre both soups with positive area   @throws InvalidInput naming the file
NormalDeviation normal_deviation(const PolygonSoup& mesh, const PolygonSoup& reference,
                                 const NormalOptions& opt = {},
                                 const std::string& mesh_name = "mesh",
                                 const std::string& reference_name = "reference");

}  // namespace mg::evaluate
