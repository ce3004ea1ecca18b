#pragma once
/// \file mesh_topology.h
/// Combinatorial checks of a polygon soup: closed, manifold, oriented, components, genus.

#include "core/mesh.h"

#include <cstddef>
#include <string>

namespace mg {

struct MeshTopology {
  std::size_t vertices = 0;  ///< vertices referenced by at least one face
  std::size_t edges = 0;     ///< distinct undirected edges
  std::size_t faces = 0;
  std::size_t boundary_edges = 0;        ///< used by exactly one face
  std::size_t nonmanifold_edges = 0;     ///< used by three or more faces
  std::size_t nonmanifold_vertices = 0;  ///< faces around the vertex form two or more fans
  std::size_t misoriented_edges = 0;     ///< two faces run along the edge in the same direction
  std::size_t components = 0;            ///< connected through shared vertices
  long euler = 0;                        ///< V - E + F
  bool closed = false;                   ///< no boundary edge
  bool manifold = false;                 ///< no non-manifold edge or vertex
  bool oriented = false;                 ///< manifold and no misoriented edge
  /// Sum of the components' genera when closed and oriented: (2 * components - euler) / 2;
  /// -1 otherwise.
  int genus = -1;
  /// The first defect found, as a sentence naming the element ("edge (3, 7) is shared by 3
  /// faces"); empty when manifold and oriented.
  std::string first_problem;
};

/// @pre every face index in range (see read_polygon_soup)
MeshTopology mesh_topology(const PolygonSoup& soup);

}  // namespace mg
