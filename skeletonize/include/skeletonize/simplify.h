#pragma once
/// \file simplify.h
/// Compact medial meshes: edge collapses ordered by Q-MAT's spherical quadric error (Li et al.,
/// ACM TOG 2015) times its stability ratio, each merged atom placed at its quadric's minimiser,
/// under a test of the loops each collapse contracts (those the balls do not cover are refused:
/// perhaps a tunnel of the envelope) and bounds on how far the merged atom's hulls may stick
/// out of the object and its samples lie outside them. See docs/algorithm.md "Simplification".

#include "core/medial_surface.h"
#include "core/mesh.h"
#include "skeletonize/union_topology.h"

#include <array>
#include <cstddef>
#include <vector>

namespace mg::skeletonize {

struct SimplifyOptions {
  /// Stop when this many atoms remain. Collapses also stop earlier when every remaining edge is
  /// refused (SimplifyStats::target_reached then false).
  std::size_t target_atoms = 1;
  /// kappa: the stability term's constant k = kappa * D^4 (D: the diagonal of the object's
  /// bounding box; the quadric error of area-weighted planes is a length^4). The cost of an edge
  /// is (E + k) * gamma^2, E the merged atom's quadric error and gamma the edge's stability
  /// ratio: with k > 0, an edge of small gamma (a ball nearly inside its neighbour: a spike) is
  /// cheap even when E is not. Default chosen by measurement (docs/algorithm.md).
  double stability_weight = 1e-8;
  /// false: the cost is E alone (no stability term; for comparisons).
  bool stability = true;
  /// Keep only the input simplices that are also simplices of the dual complex of the union of
  /// the balls (union_topology.h's union_complex(): edges between balls that meet, triangles of
  /// three with a common point, cells of four), which is homotopy equivalent to the union.
  bool union_complex = true;
  /// tau, as a fraction of D: no collapse may leave a hull of the merged atom's star (its ball,
  /// the cones of its edges, the slabs of its triangles) sticking out of the object by more
  /// than tau, or than the input atoms merged into it stuck out when that is more (estimated at
  /// interpolated balls of each hull: r - the distance from the centre to the object); and
  /// before the collapses, the simplices whose hulls stick out by more than tau are removed by
  /// elementary collapses where a free face allows. 0: neither (pure Q-MAT). The collapses'
  /// bound rises from tau / 8 to tau, doubling when a pass over the queue collapses nothing
  /// (likewise delta): the collapses that keep the envelope closest to the object go first.
  double max_excess = 1.5e-2;
  /// delta, as a fraction of D: no collapse may leave a sample of the merged atom (the samples
  /// whose poles merged into it) farther than delta outside the solid of its star (its ball,
  /// cones and slabs, and its neighbours' balls): at the time of the collapse, an upper bound
  /// on how far the envelope falls short of the object there. Later collapses of neighbours
  /// change the star and do not re-check those samples (measured: anchor_dense ends with
  /// samples 1.8 % outside for delta 1.5 %). Needs the samples; 0: no bound.
  double max_shortfall = 1.5e-2;
  /// true: each atom's quadric is built from the object's own face planes, each face's plane
  /// shared among the atoms of the samples on it (needs the samples); false: from the tangent
  /// planes of the medial mesh's slabs and cones (Q-MAT).
  bool surface_planes = true;
};

struct SimplifyStats {
  std::size_t atoms_before = 0, edges_before = 0, faces_before = 0, cells_before = 0;
  std::size_t atoms_after = 0, edges_after = 0, faces_after = 0, cells_after = 0;
  /// Input simplices not in the union's dual complex (SimplifyOptions::union_complex): dropped.
  std::size_t dropped_edges = 0, dropped_faces = 0, dropped_cells = 0;
  /// Edges added before anything else to join components of the complex whose balls meet
  /// (e.g. atoms hidden in the regular triangulation): the deepest-overlapping pair between two
  /// components first, until the complex has the union's components.
  std::size_t joined_isolated = 0;
  /// Elementary collapses before the edge collapses (each removes a maximal simplex with a free
  /// face). First the thinning: cells removed, each with a face. Then the pruning: simplices
  /// whose hull stuck out by more than tau, removed with the free face each took along (faces
  /// with an edge, cells left by the thinning with a face), and such simplices left in place
  /// because no free face allowed it.
  std::size_t thinned_cells = 0, thinned_faces = 0;
  std::size_t pruned_edges = 0, pruned_faces = 0, pruned_cells = 0, kept_excess = 0;
  /// Maximal simplices sticking out by more than tau removed alone, because the loop their
  /// removal opens or closes is covered by balls (see refused_topology).
  std::size_t removed_edges = 0, removed_faces = 0;
  std::size_t collapses = 0;
  /// Loops a-b-c contracted by the collapses done, each covered by its three balls (so no
  /// tunnel of the envelope): a 1-cycle of the complex killed, or a 2-cycle made.
  std::size_t contracted_loops = 0;
  /// The collapse would contract a loop a-b-c of the complex (a free component of
  /// Lk(a) ∩ Lk(b), docs/algorithm.md) that its three balls do not cover: perhaps a tunnel.
  std::size_t refused_topology = 0;
  std::size_t refused_outside = 0;  ///< the merged atom's centre would leave the object
  std::size_t refused_excess = 0;   ///< a hull of the merged star would stick out by more than tau
  /// a sample of the merged atoms would lie farther than delta outside the merged star
  std::size_t refused_shortfall = 0;
  /// How the merged atoms were placed (sphere_quadric.h's Placement), over the collapses done.
  std::size_t placed_minimiser = 0, placed_nearest_minimiser = 0, placed_fallback = 0;
  /// Merged atoms whose radius was clamped (no deeper overshoot of the object than the input
  /// atoms merged into them had).
  std::size_t clamped_radii = 0;
  std::size_t rounds = 0;  ///< passes over the queue (a new pass retries refused edges)
  bool target_reached = false;
  /// The complex (atoms, edges, faces and cells) before and after: components (no collapse
  /// changes them; checked at the end, a change throws TopologyError) and Euler characteristic
  /// V - E + F - T (the complex's, not the envelope's: contracted loops and pruned simplices
  /// change it; the envelope's topology is what M2 garbed from the output shows).
  long complex_components_before = 0, complex_components_after = 0;
  long complex_euler_before = 0, complex_euler_after = 0;
  double diagonal = 0;      ///< D, model units
  double worst_excess = 0;  ///< max over the output's hulls of the estimated excess, model units
  /// max over the atoms before the collapses of their samples' distance outside their star
  /// (what the shortfall bound allows them), model units
  double input_shortfall = 0;
  double max_error = 0;  ///< the largest quadric error E of a collapse done
  double seconds_setup = 0, seconds_prune = 0, seconds_quadrics = 0, seconds_collapse = 0,
         seconds_output = 0;
};

struct SimplifiedMedialMesh {
  /// Atoms by decreasing radius (ties by centre); every edge once (i < j), the faces' sides
  /// included; every face once (i < j < k), the cells' faces included; all sorted. Radii > 0.
  MedialSurface surface;
  std::vector<std::array<int, 4>> cells;  ///< the cells left (i < j < k < l), sorted
  SimplifyStats stats;
};

/// Simplifies a medial mesh to opt.target_atoms atoms (docs/algorithm.md "Simplification").
/// The complex is the atoms, the edges and faces of `mesh` with the faces' sides, and the
/// `cells` (tetrahedra, e.g. the regular triangulation's inside the object, which fill what
/// would otherwise be hollow: their four faces are taken as triangles) with their faces and
/// edges. A collapse may contract a loop of the complex only where the loop's three balls
/// cover it (so the complex's homotopy type may change, the envelope's tunnels are kept). Output
/// is the same at any thread count.
/// @param mesh   atoms with edges and faces, as written (repeats and either orientation allowed)
/// @param cells  tetrahedra over mesh's atoms (may be empty)
/// @param samples, atom_of_sample  with SimplifyOptions::surface_planes: skeletonize()'s samples
///        (the object's used vertices first, in order) and the atom each one's pole became (-1:
///        none); empty: the slabs' planes are used
/// @param dual   the union's dual complex of mesh.atoms when the caller has it
///        (Skeleton::union_complex, from skeletonize's own triangulation); computed otherwise
///        (a second regular triangulation) when SimplifyOptions::union_complex asks for it
/// @pre object a closed, manifold, consistently oriented mesh (either orientation); mesh valid
///      (validate()), radii > 0, cells' four atoms distinct and in range; samples and
///      atom_of_sample of one size, atoms in [-1, atoms), at least as many samples as the
///      object's used vertices; 1 <= opt.target_atoms <= mesh.atoms.size(); stability_weight,
///      max_excess and max_shortfall finite, >= 0; dual, if given, is union_complex(mesh.atoms)
/// @throws InvalidInput naming the object's defect, the first offending atom, cell or sample,
///         or the option; TopologyError if the complex's components changed (a bug)
SimplifiedMedialMesh simplify_medial_mesh(const PolygonSoup& object, const MedialSurface& mesh,
                                          const std::vector<std::array<int, 4>>& cells,
                                          const SimplifyOptions& opt,
                                          const std::vector<Eigen::Vector3d>& samples = {},
                                          const std::vector<int>& atom_of_sample = {},
                                          const UnionComplex* dual = nullptr);

}  // namespace mg::skeletonize
