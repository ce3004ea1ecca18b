#include "garbing/coarse_mesh.h"

#include "core/errors.h"
#include "core/union_find.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>

namespace mg::garbing {
namespace {

using Lattice = std::array<std::int64_t, 3>;

/// One directed use of an M1 edge by a face loop.
struct EdgeUse {
  int lo, hi;    // lattice vertex ids, lo < hi
  bool forward;  // the loop runs lo -> hi
  int face;
  std::size_t corner_lo, corner_hi;  // global corner ids of lo and hi in that loop
};

class Extractor {
 public:
  explicit Extractor(const Octree& tree) : tree_(tree), depth_(tree.depth) {}

  CoarseMesh run() {
    collect_faces();
    number_vertices();
    build_loops();
    return split_and_build();
  }

 private:
  // --- faces -------------------------------------------------------------------------------

  /// The one rule: for each face-adjacent pair (active leaf, inactive leaf or outside), the
  /// face of the finer of the two, oriented out of the active leaf. Leaves in parallel, faces
  /// concatenated in leaf order.
  void collect_faces() {
    const std::vector<int>& leaves = tree_.leaves;
    std::vector<std::vector<CoarseFace>> per(leaves.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::vector<int> finer;
                        for (std::size_t i = r.begin(); i != r.end(); ++i)
                          faces_of_leaf(leaves[i], per[i], finer);
                      });
    std::size_t total = 0;
    for (const auto& v : per) total += v.size();
    out_.faces.reserve(total);
    for (const auto& v : per) out_.faces.insert(out_.faces.end(), v.begin(), v.end());
  }

  void faces_of_leaf(int c, std::vector<CoarseFace>& out, std::vector<int>& finer) const {
    const OctreeCell& cell = tree_.cells[c];
    if (!cell.is_active()) return;
    auto emit = [&](int level, const Lattice& corner, int axis, int sign) {
      CoarseFace f;
      f.axis = axis;
      f.sign = sign;
      f.level = level;
      f.corner = corner;
      f.owner = c;
      out.push_back(f);
    };
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1}) {
        Lattice nb = {cell.ijk[0], cell.ijk[1], cell.ijk[2]};
        nb[axis] += sign;
        Lattice own = {cell.ijk[0], cell.ijk[1], cell.ijk[2]};
        own[axis] += sign > 0 ? 1 : 0;
        const int n = find_cell(tree_, cell.level, nb);
        if (n < 0 || (tree_.cells[n].is_leaf() && !tree_.cells[n].is_active())) {
          emit(cell.level, own, axis, sign);  // outside, or inactive and not finer
          continue;
        }
        if (tree_.cells[n].is_leaf()) continue;  // active neighbour
        std::array<int, 3> offset = {0, 0, 0};
        offset[axis] = sign;
        finer.clear();
        leaves_facing(tree_, n, offset, finer);
        for (int f : finer) {
          const OctreeCell& leaf = tree_.cells[f];
          if (leaf.is_active()) continue;
          Lattice corner = {leaf.ijk[0], leaf.ijk[1], leaf.ijk[2]};
          corner[axis] += sign > 0 ? 0 : 1;  // the finer leaf's face toward `cell`
          emit(leaf.level, corner, axis, sign);
        }
      }
  }

  /// The four corners of face f in lattice units at the deepest level, CCW seen from the side
  /// the normal points to.
  std::array<Lattice, 4> corners(const CoarseFace& f) const {
    const std::int64_t s = std::int64_t(1) << (depth_ - f.level);
    Lattice p0;
    for (int a = 0; a < 3; ++a) p0[a] = f.corner[a] * s;
    const int u = (f.axis + 1) % 3, v = (f.axis + 2) % 3;
    Lattice pu = p0, puv = p0, pv = p0;
    pu[u] += s;
    puv[u] += s;
    puv[v] += s;
    pv[v] += s;
    if (f.sign > 0) return {p0, pu, puv, pv};
    return {p0, pv, puv, pu};
  }

  void number_vertices() {
    for (const CoarseFace& f : out_.faces)
      for (const Lattice& p : corners(f)) lattice_.push_back(p);
    tbb::parallel_sort(lattice_.begin(), lattice_.end());
    lattice_.erase(std::unique(lattice_.begin(), lattice_.end()), lattice_.end());
  }

  int vertex_id(const Lattice& p) const {
    return static_cast<int>(std::lower_bound(lattice_.begin(), lattice_.end(), p) -
                            lattice_.begin());
  }

  // --- loops with hanging corners ------------------------------------------------------------

  /// An edge's line: (edge axis, the two other coordinates); a point on it: + its position.
  static std::array<std::int64_t, 4> line_point(const Lattice& p, int e) {
    return {e, p[(e + 1) % 3], p[(e + 2) % 3], p[e]};
  }

  static int edge_axis(const Lattice& p, const Lattice& q) {
    for (int a = 0; a < 3; ++a)
      if (p[a] != q[a]) return a;
    return -1;
  }

  void build_loops() {
    // Every face-edge endpoint, keyed by its line: a point strictly inside another edge on the
    // same line is a corner of an overlapping finer edge, i.e. a hanging corner.
    std::vector<std::array<std::int64_t, 4>> on_lines;
    for (const CoarseFace& f : out_.faces) {
      const auto c = corners(f);
      for (int i = 0; i < 4; ++i) {
        const int e = edge_axis(c[i], c[(i + 1) % 4]);
        on_lines.push_back(line_point(c[i], e));
        on_lines.push_back(line_point(c[(i + 1) % 4], e));
      }
    }
    tbb::parallel_sort(on_lines.begin(), on_lines.end());
    on_lines.erase(std::unique(on_lines.begin(), on_lines.end()), on_lines.end());

    loops_.resize(out_.faces.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out_.faces.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t fi = r.begin(); fi != r.end(); ++fi)
                          build_loop(out_.faces[fi], on_lines, loops_[fi]);
                      });
    for (const auto& loop : loops_) out_.hanging_corners += loop.size() - 4;
  }

  /// The face's four corners in order, each followed by the hanging corners on its edge.
  void build_loop(const CoarseFace& face, const std::vector<std::array<std::int64_t, 4>>& on_lines,
                  std::vector<int>& loop) const {
    const auto c = corners(face);
    for (int i = 0; i < 4; ++i) {
      const Lattice& p = c[i];
      const Lattice& q = c[(i + 1) % 4];
      loop.push_back(vertex_id(p));
      const int e = edge_axis(p, q);
      auto key = line_point(p, e);
      key[3] = std::min(p[e], q[e]);
      auto first = std::upper_bound(on_lines.begin(), on_lines.end(), key);
      key[3] = std::max(p[e], q[e]);
      auto last = std::lower_bound(on_lines.begin(), on_lines.end(), key);
      if (first == last) continue;
      const std::size_t begin = loop.size();
      for (auto it = first; it != last; ++it) {
        Lattice h = p;
        h[e] = (*it)[3];
        loop.push_back(vertex_id(h));
      }
      if (p[e] > q[e]) std::reverse(loop.begin() + static_cast<std::ptrdiff_t>(begin), loop.end());
    }
  }

  // --- non-manifold places, then the mesh ----------------------------------------------------

  /// Signs (along the two axes other than `e`, in increasing axis order) of the active
  /// quadrant that face f bounds next to the edge through lattice point p along axis e.
  int active_quadrant(const CoarseFace& f, const Lattice& p, int e) const {
    const auto c = corners(f);
    int code = 0, bit = 0;
    for (int a = 0; a < 3; ++a) {
      if (a == e) continue;
      int side;
      if (a == f.axis) {
        side = -f.sign;  // the active leaf lies behind the face
      } else {
        const std::int64_t twice_centre = c[0][a] + c[2][a];
        side = twice_centre > 2 * p[a] ? 1 : -1;
      }
      code |= (side > 0 ? 1 : 0) << bit++;
    }
    return code;
  }

  [[noreturn]] void defect(const std::string& what) const {
    throw TopologyError("M1 extraction: " + what);
  }

  CoarseMesh split_and_build() {
    std::vector<std::size_t> first_corner(loops_.size() + 1, 0);
    for (std::size_t f = 0; f < loops_.size(); ++f)
      first_corner[f + 1] = first_corner[f] + loops_[f].size();
    const std::size_t n_corners = first_corner.back();

    std::vector<EdgeUse> uses;
    uses.reserve(n_corners);
    for (std::size_t f = 0; f < loops_.size(); ++f) {
      const auto& loop = loops_[f];
      const std::size_t k = loop.size();
      for (std::size_t i = 0; i < k; ++i) {
        const int a = loop[i], b = loop[(i + 1) % k];
        const std::size_t ca = first_corner[f] + i, cb = first_corner[f] + (i + 1) % k;
        if (a < b)
          uses.push_back({a, b, true, static_cast<int>(f), ca, cb});
        else
          uses.push_back({b, a, false, static_cast<int>(f), cb, ca});
      }
    }
    tbb::parallel_sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
      return std::tie(x.lo, x.hi, x.face, x.corner_lo) < std::tie(y.lo, y.hi, y.face, y.corner_lo);
    });

    UnionFind corners_of(n_corners);
    auto join = [&](const EdgeUse& x, const EdgeUse& y) {
      if (x.forward == y.forward) defect("two faces run along an edge in the same direction");
      corners_of.unite(x.corner_lo, y.corner_lo);
      corners_of.unite(x.corner_hi, y.corner_hi);
    };
    std::vector<std::array<std::size_t, 2>> pinched_sides;  // pairs of uses, one per side
    for (std::size_t i = 0; i < uses.size();) {
      std::size_t j = i;
      while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
      if (j - i == 2) {
        join(uses[i], uses[i + 1]);
      } else if (j - i == 4) {
        // Two active leaves meeting only along this edge: pair the faces per active side.
        const Lattice& p = lattice_[uses[i].lo];
        const int e = edge_axis(p, lattice_[uses[i].hi]);
        std::array<std::vector<std::size_t>, 4> by_quadrant;
        for (std::size_t k = i; k < j; ++k)
          by_quadrant[active_quadrant(out_.faces[uses[k].face], p, e)].push_back(k);
        for (const auto& q : by_quadrant) {
          if (q.empty()) continue;
          if (q.size() != 2) defect("an edge shared by 4 faces does not split into two sides");
          join(uses[q[0]], uses[q[1]]);
          pinched_sides.push_back({q[0], q[1]});
        }
      } else {
        defect("an edge is shared by " + std::to_string(j - i) + " faces");
      }
      i = j;
    }

    // One vertex per class of corners around each lattice point.
    std::vector<int> new_id(n_corners, -1);
    std::vector<Lattice> points;
    PolygonSoup soup;
    soup.faces.resize(loops_.size());
    for (std::size_t f = 0; f < loops_.size(); ++f)
      for (std::size_t i = 0; i < loops_[f].size(); ++i) {
        const std::size_t root = corners_of.find(first_corner[f] + i);
        if (new_id[root] < 0) {
          new_id[root] = static_cast<int>(points.size());
          points.push_back(lattice_[loops_[f][i]]);
        }
        soup.faces[f].push_back(new_id[root]);
      }
    out_.split_vertices = points.size() - lattice_.size();

    const double unit = std::ldexp(tree_.root_side, -depth_);
    auto world = [&](const Lattice& p) {
      return tree_.to_world(Eigen::Vector3d(p[0] * unit, p[1] * unit, p[2] * unit));
    };
    soup.points.reserve(points.size());
    for (const Lattice& p : points) soup.points.push_back(world(p));

    // A pinched edge whose two sides still share both end vertices (the sheets are joined
    // elsewhere around both ends) would be a double edge: give each side its own midpoint.
    std::vector<std::vector<std::pair<std::size_t, int>>> inserts(loops_.size());
    for (std::size_t s = 0; s < pinched_sides.size(); s += 2) {
      const EdgeUse& a = uses[pinched_sides[s][0]];
      const EdgeUse& b = uses[pinched_sides[s + 1][0]];
      if (corners_of.find(a.corner_lo) != corners_of.find(b.corner_lo) ||
          corners_of.find(a.corner_hi) != corners_of.find(b.corner_hi))
        continue;
      for (std::size_t side = s; side < s + 2; ++side) {
        const int mid = static_cast<int>(soup.points.size());
        soup.points.push_back((world(lattice_[a.lo]) + world(lattice_[a.hi])) / 2);
        ++out_.pinch_midpoints;
        for (std::size_t use : pinched_sides[side]) {
          const EdgeUse& u = uses[use];
          const std::size_t from = u.forward ? u.corner_lo : u.corner_hi;
          inserts[u.face].push_back({from - first_corner[u.face], mid});
        }
      }
    }
    for (std::size_t f = 0; f < inserts.size(); ++f) {
      if (inserts[f].empty()) continue;
      std::sort(inserts[f].begin(), inserts[f].end());
      std::vector<int> loop;
      auto next = inserts[f].begin();
      for (std::size_t i = 0; i < soup.faces[f].size(); ++i) {
        loop.push_back(soup.faces[f][i]);
        for (; next != inserts[f].end() && next->first == i; ++next) loop.push_back(next->second);
      }
      soup.faces[f] = std::move(loop);
    }
    out_.face_centres.reserve(out_.faces.size());
    for (const CoarseFace& f : out_.faces) {
      const auto c = corners(f);
      Eigen::Vector3d centre;
      for (int a = 0; a < 3; ++a) centre[a] = 0.5 * static_cast<double>(c[0][a] + c[2][a]) * unit;
      out_.face_centres.push_back(tree_.to_world(centre));
    }
    out_.mesh = mesh_from_manifold_soup(soup, "M1");
    return std::move(out_);
  }

  const Octree& tree_;
  const int depth_;
  CoarseMesh out_;
  std::vector<Lattice> lattice_;         // distinct face corners, sorted
  std::vector<std::vector<int>> loops_;  // per face: lattice vertex ids with hanging corners
};

}  // namespace

CoarseMesh extract_coarse_mesh(const Octree& tree) {
  if (tree.cells.empty()) throw InvalidInput("extract_coarse_mesh: empty octree");
  return Extractor(tree).run();
}

}  // namespace mg::garbing
