// Thinning of dense atoms: balls contained in a nearby kept ball (or covered by the union of
// nearby kept balls) up to a slack are left out, greedily, in an order that visits space block
// by block.
#include "garbing/thin_atoms.h"

#include "core/errors.h"
#include "core/medial_surface.h"
#include "core/timer.h"
#include "garbing/target_shape.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>

namespace mg::garbing {
namespace {

using Cell = std::array<std::int64_t, 3>;

/// Open addressing from a grid cell to the last kept ball in it (the others follow through
/// `next`); a cell is identified by the cell of its first ball.
class KeptGrid {
 public:
  KeptGrid(std::size_t balls, const std::vector<Cell>& cell_of)
      : cell_of_(cell_of), next_(balls, -1) {
    std::size_t size = 16;
    while (size < 2 * balls) size *= 2;
    slot_.assign(size, -1);
    mask_ = size - 1;
  }
  /// The last kept ball of the cell, -1 if none.
  int head(const Cell& c) const { return slot_[find(c)]; }
  int next(int i) const { return next_[static_cast<std::size_t>(i)]; }
  void insert(int i) {
    const std::size_t s = find(cell_of_[static_cast<std::size_t>(i)]);
    next_[static_cast<std::size_t>(i)] = slot_[s];
    slot_[s] = i;
  }

 private:
  std::size_t find(const Cell& c) const {
    std::uint64_t h = static_cast<std::uint64_t>(c[0]) * 0x9e3779b97f4a7c15ULL ^
                      static_cast<std::uint64_t>(c[1]) * 0xc2b2ae3d27d4eb4fULL ^
                      static_cast<std::uint64_t>(c[2]) * 0x165667b19e3779f9ULL;
    std::size_t s = static_cast<std::size_t>(h ^ h >> 29) & mask_;
    while (slot_[s] >= 0 && cell_of_[static_cast<std::size_t>(slot_[s])] != c) s = (s + 1) & mask_;
    return s;
  }
  const std::vector<Cell>& cell_of_;
  std::vector<int> next_;
  std::vector<int> slot_;
  std::size_t mask_ = 0;
};

/// The atoms on a grid, and the order in which a greedy pass visits them.
struct GridOrder {
  Eigen::Vector3d origin;     ///< the centres' bounding box's min corner
  double side = 0;            ///< of a cell
  std::vector<Cell> cell_of;  ///< each atom's cell
  std::vector<int> order;     ///< the visit
};

/// Cells of side h, or coarser where the atoms span more than 2^24 cells so that the blocks'
/// Morton codes (21 bits of cell / 8) do not wrap (a search then only reaches farther); the
/// order: blocks of 8 x 8 x 8 cells in Morton order (one region at a time), in a block by
/// decreasing radius, then by index (a strict total order).
GridOrder grid_order(const std::vector<MedialAtom>& a, double h) {
  const std::size_t n = a.size();
  Eigen::AlignedBox3d box;
  for (const MedialAtom& b : a) box.extend(b.centre);
  GridOrder g;
  g.origin = box.min();
  g.side = std::max(h, box.sizes().maxCoeff() * 0x1p-24);
  g.cell_of.resize(n);
  std::vector<std::uint64_t> block_key(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const Eigen::Vector3d q = (a[i].centre - g.origin) / g.side;
    for (int k = 0; k < 3; ++k) g.cell_of[i][k] = static_cast<std::int64_t>(std::floor(q[k]));
    block_key[i] = morton_code(static_cast<std::uint64_t>(g.cell_of[i][0] >> 3),
                               static_cast<std::uint64_t>(g.cell_of[i][1] >> 3),
                               static_cast<std::uint64_t>(g.cell_of[i][2] >> 3));
  });
  g.order.resize(n);
  std::iota(g.order.begin(), g.order.end(), 0);
  tbb::parallel_sort(g.order.begin(), g.order.end(), [&](int i, int j) {
    if (block_key[i] != block_key[j]) return block_key[i] < block_key[j];
    if (a[i].radius != a[j].radius) return a[i].radius > a[j].radius;
    return i < j;
  });
  return g;
}

/// The atoms whose flag is set, in their order; their indices (index_of[i], or i) to kept_index.
MedialSurface kept_atoms(const std::vector<MedialAtom>& a, const std::vector<char>& kept,
                         const std::vector<int>* index_of, std::vector<int>* kept_index) {
  MedialSurface out;
  if (kept_index) kept_index->clear();
  for (std::size_t i = 0; i < a.size(); ++i)
    if (kept[i]) {
      out.atoms.push_back(a[i]);
      if (kept_index) kept_index->push_back(index_of ? (*index_of)[i] : static_cast<int>(i));
    }
  return out;
}

}  // namespace

MedialSurface thin_atoms(const MedialSurface& atoms, double slack, ThinStats* stats,
                         std::vector<int>* kept_index) {
  const Stopwatch clock;
  if (!(slack >= 0) || !std::isfinite(slack))
    throw InvalidInput("thin_atoms: the slack must be finite and >= 0, got " +
                       std::to_string(slack));
  if (!atoms.edges.empty() || !atoms.faces.empty())
    throw InvalidInput(
        "thin_atoms: a medial mesh's envelope (edges or faces) is not a union of balls");
  validate(atoms);
  require_positive_radii(atoms);
  const std::vector<MedialAtom>& a = atoms.atoms;
  const std::size_t n = a.size();
  std::vector<char> kept(n, 1);
  if (slack > 0 && n > 1) {
    // Grid of side h = 8 slack: the centres within 4 slack of a point lie in the 2 x 2 x 2
    // cells nearest to it (up to the rounding of their cell coordinates).
    const GridOrder g = grid_order(a, 8 * slack);
    KeptGrid grid(n, g.cell_of);
    for (int i : g.order) {
      const Eigen::Vector3d& c = a[i].centre;
      const double r = a[i].radius;
      const Eigen::Vector3d q = (c - g.origin) / g.side;
      const Cell base = g.cell_of[i];
      std::array<int, 3> step;
      for (int k = 0; k < 3; ++k) step[k] = q[k] - static_cast<double>(base[k]) < 0.5 ? -1 : 1;
      bool contained = false;
      for (int k = 0; k < 8 && !contained; ++k) {
        const Cell cell = {base[0] + (k & 1) * step[0], base[1] + (k >> 1 & 1) * step[1],
                           base[2] + (k >> 2 & 1) * step[2]};
        for (int j = grid.head(cell); j >= 0; j = grid.next(j))
          if ((a[j].centre - c).norm() + r <= a[j].radius + slack) {
            contained = true;
            break;
          }
      }
      if (contained)
        kept[i] = 0;
      else
        grid.insert(i);
    }
  }
  const MedialSurface out = kept_atoms(a, kept, nullptr, kept_index);
  if (stats) {
    stats->slack = slack;
    stats->kept = out.atoms.size();
    stats->dropped = n - out.atoms.size();
    stats->covered = 0;
    stats->seconds = clock.seconds();
  }
  return out;
}

namespace {

/// The part of a ball's sphere S (centre c, radius r) inside another ball grown by the slack
/// (centre c_j, radius R): the cap of unit axis u = (c_j - c) / |c_j - c| and angular radius
/// theta, cos theta = (r^2 + d^2 - R^2) / (2 r d), d = |c_j - c|.
struct Cap {
  Eigen::Vector3d u;
  double c, s;  ///< cos theta, sin theta
};

/// What a grown ball does to the sphere of `ball`.
enum class Meets { contains, cap, nothing };

/// The cap the ball (cj, rj) grown by the slack cuts from the sphere of `ball`, if that grown
/// ball holds the centre of `ball` (the covering proof uses only such balls).
Meets cap_of(const MedialAtom& ball, const Eigen::Vector3d& cj, double rj, double slack, Cap& cap) {
  const double big = rj + slack, r = ball.radius;
  const Eigen::Vector3d v = cj - ball.centre;
  const double d = v.norm();
  if (d + r <= big) return Meets::contains;
  if (d > big || d == 0) return Meets::nothing;  // d == 0: a smaller concentric ball
  const double c = (r * r + d * d - big * big) / (2 * r * d);
  if (c >= 1) return Meets::nothing;
  cap.u = v / d;
  cap.c = std::max(c, -1.0);
  cap.s = std::sqrt(1 - cap.c * cap.c);
  return Meets::cap;
}

/// An angle's monotone stand-in in [0, 4): the diamond angle of (x, y) != 0.
double diamond(double x, double y) {
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}

/// An open arc of a circle, (start, end) in diamond angles; end < start if it passes 0.
struct Arc {
  double start, end;
  bool operator<(const Arc& o) const { return start < o.start; }
};

/// Whether the open arcs cover the circle.
bool arcs_cover_circle(std::vector<Arc>& arcs) {
  double reach = 0;  // [0, reach) covered by the arcs through 0
  for (const Arc& x : arcs)
    if (x.end < x.start) reach = std::max(reach, x.end);
  if (reach <= 0) return false;  // 0 itself is not covered
  std::sort(arcs.begin(), arcs.end());
  for (const Arc& x : arcs) {
    if (x.start >= reach) return false;  // the point `reach` is not covered
    if (x.end < x.start) return true;    // reaches 4 = 0
    reach = std::max(reach, x.end);
  }
  return false;
}

/// Whether the caps cover the sphere (see union_covers_ball()). Reorders and shortens `caps`;
/// `arcs` is scratch.
bool caps_cover_sphere(std::vector<Cap>& caps, std::vector<Arc>& arcs) {
  // Only the caps no other one holds, the largest first: cap j lies in cap k if theta_j <=
  // theta_k and angle(u_j, u_k) <= theta_k - theta_j, i.e. u_j . u_k >= cos(theta_k - theta_j).
  // Leaving out a cap can only fail a proof, so nearly equal caps (within 1e-12) go too: an
  // equal cap's circle lies on the other's, not inside it.
  std::sort(caps.begin(), caps.end(), [](const Cap& x, const Cap& y) { return x.c < y.c; });
  std::size_t m = 0;
  double area = 0;  // the caps' areas / 2 pi: the sphere's is 2
  for (std::size_t j = 0; j < caps.size(); ++j) {
    bool inside = false;
    for (std::size_t k = 0; k < m && !inside; ++k)
      inside = caps[j].u.dot(caps[k].u) >= caps[k].c * caps[j].c + caps[k].s * caps[j].s - 1e-12;
    if (!inside) {
      caps[m++] = caps[j];
      area += 1 - caps[j].c;
    }
  }
  caps.resize(m);
  if (m == 0 || area < 2) return false;
  constexpr double shrink = 1e-9;  // of each arc's ends, in diamond angle
  for (std::size_t j = 0; j < m; ++j) {
    const Cap& cj = caps[j];
    // Cap j's circle: x(phi) = c_j u_j + s_j (cos phi e1 + sin phi e2).
    Eigen::Vector3d e1 = std::abs(cj.u.x()) < 0.9 ? Eigen::Vector3d::UnitX().cross(cj.u)
                                                  : Eigen::Vector3d::UnitY().cross(cj.u);
    e1.normalize();
    const Eigen::Vector3d e2 = cj.u.cross(e1);
    arcs.clear();
    bool inside_one = false;
    for (std::size_t k = 0; k < m && !inside_one; ++k) {
      if (k == j) continue;
      const Cap& ck = caps[k];
      // x(phi) inside cap k: x . u_k > c_k, i.e. a cos phi + b sin phi > e.
      const double a = cj.s * e1.dot(ck.u), b = cj.s * e2.dot(ck.u);
      const double e = ck.c - cj.c * cj.u.dot(ck.u);
      const double rho = std::hypot(a, b);
      if (e < -rho - 1e-12) {
        inside_one = true;  // the whole circle
        continue;
      }
      // Circles nearly coaxial (rho tiny): their arcs' directions would be rounding's.
      if (e >= rho || rho < 1e-9) continue;
      // The arc of half-width w = acos(e / rho) around (a, b) / rho.
      const double x0 = a / rho, y0 = b / rho, cw = std::max(e / rho, -1.0);
      const double sw = std::sqrt(1 - cw * cw);
      const double start = diamond(x0 * cw + y0 * sw, y0 * cw - x0 * sw) + shrink;
      const double end = diamond(x0 * cw - y0 * sw, y0 * cw + x0 * sw) - shrink;
      if (start >= 4 || end <= 0) continue;  // an end too near 0 to tell: left out
      arcs.push_back({start, end});
    }
    if (!inside_one && !arcs_cover_circle(arcs)) return false;
  }
  return true;
}

}  // namespace

bool union_covers_ball(const MedialAtom& ball, const std::vector<MedialAtom>& others,
                       double slack) {
  std::vector<Cap> caps;
  Cap cap;
  for (const MedialAtom& o : others) {
    const Meets m = cap_of(ball, o.centre, o.radius, slack, cap);
    if (m == Meets::contains) return true;
    if (m == Meets::cap) caps.push_back(cap);
  }
  std::vector<Arc> arcs;
  return caps_cover_sphere(caps, arcs);
}

MedialSurface thin_atoms_by_cover(const MedialSurface& atoms, double slack, ThinStats* stats,
                                  std::vector<int>* kept_index) {
  const Stopwatch clock;
  if (!(slack >= 0) || !std::isfinite(slack))
    throw InvalidInput("thin_atoms_by_cover: the slack must be finite and >= 0, got " +
                       std::to_string(slack));
  // First the containment pass at half the slack (it checks the preconditions): cheap, it
  // leaves the cover pass far fewer balls to prove.
  std::vector<int> first_index;
  MedialSurface first = thin_atoms(atoms, slack / 2, nullptr, &first_index);
  const std::vector<MedialAtom>& a = first.atoms;
  const std::size_t n = a.size();
  const double half = slack / 2;
  std::vector<char> kept(n, 1);
  std::size_t covered = 0;
  if (half > 0 && n > 1) {
    const GridOrder g = grid_order(a, std::sqrt(2 * characteristic_radius(first) * half));
    KeptGrid grid(n, g.cell_of);
    auto neighbours = [&](int i, auto&& visit) {
      const Cell& base = g.cell_of[static_cast<std::size_t>(i)];
      for (int k = 0; k < 27; ++k) {
        const Cell cell = {base[0] + k % 3 - 1, base[1] + k / 3 % 3 - 1, base[2] + k / 9 - 1};
        for (int j = grid.head(cell); j >= 0; j = grid.next(j))
          if (!visit(j)) return;
      }
    };
    // Seeds: a ball with no kept centre within sqrt(2 r half) is kept. A neighbour of equal
    // radius that near covers the poles of its sphere, so that nearly every other ball then
    // has kept balls around it that cover it.
    std::vector<char> seed(n, 0);
    for (int i : g.order) {
      const double reach2 = 2 * a[i].radius * half;
      bool near = false;
      neighbours(i, [&](int j) {
        near = (a[j].centre - a[i].centre).squaredNorm() < reach2;
        return !near;
      });
      if (!near) {
        seed[i] = 1;
        grid.insert(i);
      }
    }
    std::vector<Cap> caps;
    std::vector<Arc> arcs;
    for (int i : g.order) {
      if (seed[i]) continue;
      caps.clear();
      bool contained = false;
      Cap cap;
      neighbours(i, [&](int j) {
        const Meets m = cap_of(a[i], a[j].centre, a[j].radius, half, cap);
        if (m == Meets::cap) caps.push_back(cap);
        contained = m == Meets::contains;
        return !contained;
      });
      if (contained || caps_cover_sphere(caps, arcs)) {
        kept[i] = 0;
        ++covered;
      } else {
        grid.insert(i);
      }
    }
  }
  const MedialSurface out = kept_atoms(a, kept, &first_index, kept_index);
  if (stats) {
    stats->slack = slack;
    stats->kept = out.atoms.size();
    stats->dropped = atoms.atoms.size() - out.atoms.size();
    stats->covered = covered;
    stats->seconds = clock.seconds();
  }
  return out;
}

}  // namespace mg::garbing
