#pragma once
// Internal to mg::skeletonize: a simplicial complex of dimension <= 3 over atom indices, with the
// two operations the simplification needs:
// - edge collapses, with the components of Lk(a) ∩ Lk(b) that tell which loops a collapse
//   contracts (free_link_components);
// - elementary collapses: a maximal simplex removed with a free face (a face of it and of no
//   other simplex), which keep the homotopy type.
// Each vertex keeps its star as three sorted lists: its neighbours, the opposite edges of its
// triangles and the opposite triangles of its tetrahedra. A simplex is stored once per vertex.

#include <array>
#include <cstddef>
#include <vector>

namespace mg::skeletonize::detail {

using Pair = std::array<int, 2>;
using Triple = std::array<int, 3>;
using Quad = std::array<int, 4>;

class MedialComplex {
 public:
  /// @param vertices  number of vertices (0 .. vertices - 1), all alive, isolated or not
  /// @pre every simplex sorted increasingly, distinct vertices in range, listed once, and the
  ///      lists closed under faces (each side of a triangle an edge, each face of a tetrahedron
  ///      a triangle)
  MedialComplex(int vertices, const std::vector<Pair>& edges, const std::vector<Triple>& triangles,
                const std::vector<Quad>& tetrahedra);

  int vertex_slots() const { return static_cast<int>(neighbours_.size()); }
  bool alive(int v) const { return alive_[v] != 0; }
  long vertices() const { return vertices_; }
  long edges() const { return edges_; }
  long triangles() const { return triangles_; }
  long tetrahedra() const { return tetrahedra_; }
  /// V - E + F - T: the Euler characteristic of the complex (as a space).
  long euler() const { return vertices_ - edges_ + triangles_ - tetrahedra_; }
  /// Connected components (through edges) among the alive vertices.
  long components() const;

  const std::vector<int>& neighbours(int v) const { return neighbours_[v]; }
  /// The edges (x, y), x < y, with {v, x, y} a triangle.
  const std::vector<Pair>& triangle_links(int v) const { return triangle_links_[v]; }
  /// The triangles (x, y, z), x < y < z, with {v, x, y, z} a tetrahedron.
  const std::vector<Triple>& tetrahedron_links(int v) const { return tetrahedron_links_[v]; }

  bool has_edge(int u, int v) const;
  bool has_triangle(const Triple& t) const;
  bool has_tetrahedron(const Quad& t) const;
  /// The triangles containing edge {u, v}; the tetrahedra containing triangle t.
  int triangles_on_edge(int u, int v) const;
  int tetrahedra_on_triangle(const Triple& t) const;

  /// The components of I = Lk(a) ∩ Lk(b) holding no vertex of Lk(ab) (the c of the triangles
  /// abc), each as its vertices, sorted. Collapsing {a, b} is a homotopy equivalence when I is
  /// Lk(ab) (the link condition); in general the contraction glues a cone onto the complex along
  /// a suspension of X = I with a cone over Lk(ab), and Mayer-Vietoris says: cycles of X only
  /// change b2 (and b3), while each further component of X (each free component of I) contracts
  /// the loop a-b-c-a, c any vertex of it: it kills a 1-cycle when that loop is not a boundary,
  /// and adds a 2-cycle (a bubble) when it is. b0 never changes. @pre has_edge(a, b)
  std::vector<std::vector<int>> free_link_components(int a, int b) const;

  /// Merges `gone` into `keep` (edge collapse): every simplex with `gone` takes `keep` instead,
  /// those with both degenerate onto a face they already have, duplicates merge.
  /// @pre has_edge(keep, gone)
  void collapse(int keep, int gone);

  /// Removes a maximal simplex (2 to 4 vertices, sorted; no coface). @pre present and maximal
  void remove_maximal(const std::vector<int>& simplex);

  /// The simplices of the alive vertices, each once, sorted.
  std::vector<Pair> edge_list() const;
  std::vector<Triple> triangle_list() const;
  std::vector<Quad> tetrahedron_list() const;

 private:
  std::vector<std::vector<int>> neighbours_;
  std::vector<std::vector<Pair>> triangle_links_;
  std::vector<std::vector<Triple>> tetrahedron_links_;
  std::vector<char> alive_;
  long vertices_ = 0, edges_ = 0, triangles_ = 0, tetrahedra_ = 0;
};

}  // namespace mg::skeletonize::detail
