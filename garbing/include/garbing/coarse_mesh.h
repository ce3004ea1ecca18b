#pragma once
/// \file coarse_mesh.h
/// Step 2 of the garbing: the coarse mesh M1, the boundary of the active leaves of the octree
/// (paper section 3.2, docs/algorithm.md "Step 2").

#include "core/mesh.h"
#include "garbing/octree.h"

#include <array>
#include <cstdint>
#include <vector>

namespace mg::garbing {

/// One face of M1: an axis-aligned square of the octree lattice.
struct CoarseFace {
  int axis = 0;   ///< normal axis in the root frame (0, 1, 2)
  int sign = 1;   ///< +1 or -1: the normal points along sign * axis, out of the active leaf
  int level = 0;  ///< the square's side is Octree::side(level)
  /// Minimal corner of the square in lattice units at `level` (component `axis` = its plane).
  std::array<std::int64_t, 3> corner = {0, 0, 0};
  int owner = -1;  ///< the active leaf the face bounds (index in Octree::cells)
};

/// M1 and what step 3 needs to know about its faces.
struct CoarseMesh {
  /// Closed, oriented 2-manifold polygon mesh in world coordinates, faces CCW from outside.
  /// Hanging corners are part of the faces' vertex loops (faces are never split).
  Mesh mesh;
  std::vector<CoarseFace> faces;              ///< per mesh face, same order
  std::vector<Eigen::Vector3d> face_centres;  ///< centre of each face's square, world
  std::size_t hanging_corners = 0;            ///< corners inserted into coarser faces' loops
  std::size_t split_vertices = 0;             ///< extra vertex copies made at non-manifold places
  /// Midpoints given to each side of an edge where two sheets touch along the edge but are
  /// joined around both its ends (a double edge otherwise); such a midpoint has valence 2.
  std::size_t pinch_midpoints = 0;
};

/// Step 2: for every face-adjacent pair (active leaf, inactive leaf or outside of the root),
/// the face of the finer of the two, oriented out of the active leaf. Active cells are
/// 6-connected, inactive ones 26-connected: where active leaves meet only along an edge or at
/// a corner, the edge or vertex is duplicated per side, so each side closes on its own.
/// @pre `tree` from build_octree
/// @throws TopologyError if the result is not a closed oriented 2-manifold (an internal defect)
CoarseMesh extract_coarse_mesh(const Octree& tree);

}  // namespace mg::garbing
