#pragma once
/// \file frame.h
/// The frame the garbing works in: G, the octree, M1 and M2 are computed in the principal frame
/// of the atom centres, whose cube [0, side]^3 is the octree's root. Only M1 and M2 go back to
/// world coordinates.

#include "core/medial_surface.h"

#include <Eigen/Core>

namespace mg::garbing {

/// A rigid frame: local = axes^T (world - origin), axes orthonormal and right-handed.
struct Frame {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< the local axes as columns
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();    ///< world position of the local origin
  /// Side of the cube [0, cube_side]^3, model units, that holds every ball in local
  /// coordinates; 0 for a frame chosen without one (the world frame).
  double cube_side = 0;

  Eigen::Vector3d to_local(const Eigen::Vector3d& world) const {
    return axes.transpose() * (world - origin);
  }
  Eigen::Vector3d to_world(const Eigen::Vector3d& local) const { return origin + axes * local; }
  /// The identity: local coordinates are world coordinates (copied, not transformed).
  bool is_world() const { return axes == Eigen::Matrix3d::Identity() && origin.isZero(0); }
};

/// The garbing's frame of a set of atoms (paper section 3.1): the principal axes of the atom
/// centres as right-handed columns, largest variance first, each of the first two with its
/// largest component positive (the identity when two eigenvalues are repeated: one atom, two
/// atoms, a ring, a regular solid); the origin at the low corner of the tightest cube around
/// the balls in those axes, centred on their bounding box, no padding.
/// @pre atoms valid (see validate)   @throws InvalidInput
Frame bounding_cube_frame(const MedialSurface& atoms);

}  // namespace mg::garbing
