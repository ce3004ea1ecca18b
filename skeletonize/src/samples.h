#pragma once
// Internal to mg::skeletonize: the input check and the surface samples whose poles are sought.

#include "skeletonize/poles.h"

#include <string>
#include <vector>

namespace mg::skeletonize::detail {

/// @throws InvalidInput naming `name` unless the mesh is non-empty, valid (validate_soup),
///         closed, manifold and oriented
void check_closed_mesh(const PolygonSoup& mesh, const std::string& name);

/// The samples of opt: the referenced vertices, then the edge midpoints (each edge once, in
/// order), then the random area-uniform points (counter-based stream: sample k depends only on
/// the seed and k).
std::vector<Eigen::Vector3d> make_samples(const PolygonSoup& mesh, const SkeletonOptions& opt);

}  // namespace mg::skeletonize::detail
