// The generated medial meshes (shapes.h): valid, deterministic simplicial complexes of the
// documented sizes whose envelopes are connected, with the geometric separations their
// documented topology relies on.
#include "core/errors.h"
#include "core/medial_surface.h"
#include "core/shapes.h"
#include "core/union_find.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using Eigen::Vector3d;
using Edge = std::array<int, 2>;

struct Generator {
  std::string name;
  std::function<mg::MedialSurface()> make;
  std::size_t atoms, edges, faces;
  int euler;  ///< V - E + F of the complex: 1 contractible, 0 a loop
};

const std::vector<Generator>& generators() {
  static const std::vector<Generator> all = {
      {"capsule", [] { return mg::make_medial_capsule(); }, 2, 1, 0, 1},
      {"slab", [] { return mg::make_medial_slab(); }, 3, 3, 1, 1},
      {"ring", [] { return mg::make_medial_ring(); }, 16, 16, 0, 0},
      {"disc", [] { return mg::make_medial_disc(); }, 37, 90, 54, 1},
      {"sheets", [] { return mg::make_medial_sheets(); }, 8, 13, 6, 1},
      {"hand", [] { return mg::make_medial_hand(); }, 34, 51, 18, 1},
  };
  return all;
}

std::pair<int, int> key(int i, int j) { return {std::min(i, j), std::max(i, j)}; }

/// Components of the envelope's primitives: atoms joined through edges and faces.
std::size_t components(const mg::MedialSurface& s) {
  mg::UnionFind u(s.atoms.size());
  for (const auto& e : s.edges) u.unite(e[0], e[1]);
  for (const auto& f : s.faces) {
    u.unite(f[0], f[1]);
    u.unite(f[1], f[2]);
  }
  std::set<std::size_t> roots;
  for (std::size_t i = 0; i < s.atoms.size(); ++i) roots.insert(u.find(i));
  return roots.size();
}

/// Distance between the segments [p0, p1] and [q0, q1] (Ericson, Real-Time Collision Detection
/// 5.1.9), for segments of positive length.
double segment_distance(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                        const Vector3d& q1) {
  const Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2), denom = a * e - b * b;
  double s = denom > 1e-15 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return ((p0 + s * d1) - (q0 + t * d2)).norm();
}

/// Minimum of a convex function on [0, 1] (ternary search).
template <class F>
double minimum_on_unit_interval(const F& f) {
  double lo = 0, hi = 1;
  for (int k = 0; k < 80; ++k) {
    const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
    if (f(a) < f(b))
      hi = b;
    else
      lo = a;
  }
  return f((lo + hi) / 2);
}

/// Gap between the cones of two edges: positive iff they are disjoint. A cone (the hull of two
/// balls) is the union of the balls of linearly interpolated centre and radius, so the gap is
/// the minimum over (u, v) in [0, 1]^2 of |c_a(u) - c_b(v)| - r_a(u) - r_b(v), a convex function.
double cone_gap(const mg::MedialSurface& s, const Edge& a, const Edge& b) {
  auto at = [&](const Edge& e, double t) {
    const auto &p = s.atoms[e[0]], &q = s.atoms[e[1]];
    return std::make_pair(Vector3d((1 - t) * p.centre + t * q.centre),
                          (1 - t) * p.radius + t * q.radius);
  };
  return minimum_on_unit_interval([&](double u) {
    const auto [ca, ra] = at(a, u);
    return minimum_on_unit_interval([&, ca = ca, ra = ra](double v) {
      const auto [cb, rb] = at(b, v);
      return (ca - cb).norm() - ra - rb;
    });
  });
}

double ball_gap(const mg::MedialSurface& s, int i, int j) {
  return (s.atoms[i].centre - s.atoms[j].centre).norm() - s.atoms[i].radius - s.atoms[j].radius;
}

TEST(MedialShapes, SizesValidityAndOneComponent) {
  for (const Generator& g : generators()) {
    SCOPED_TRACE(g.name);
    const mg::MedialSurface s = g.make();
    EXPECT_NO_THROW(mg::validate(s));
    EXPECT_EQ(s.atoms.size(), g.atoms);
    EXPECT_EQ(s.edges.size(), g.edges);
    EXPECT_EQ(s.faces.size(), g.faces);
    for (const auto& a : s.atoms) {
      EXPECT_GT(a.radius, 0);
      EXPECT_LE((a.centre.cwiseAbs().array() + a.radius).maxCoeff(), 1.5);
    }
    EXPECT_EQ(components(s), 1u);
  }
}

TEST(MedialShapes, NoTwoBallsAreNearlyTangent) {
  // Exactly tangent balls (touching at one point) are degenerate for the garbing's octree.
  for (const Generator& g : generators()) {
    SCOPED_TRACE(g.name);
    const mg::MedialSurface s = g.make();
    const int n = static_cast<int>(s.atoms.size());
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        EXPECT_GE(std::abs(ball_gap(s, i, j)), 0.015) << "atoms " << i << ", " << j;
  }
}

TEST(MedialShapes, AreSimplicialComplexes) {
  // Every face side is an edge, no edge or face repeats: V - E + F is the Euler characteristic
  // of the complex (1 for the contractible ones, 0 for the ring).
  for (const Generator& g : generators()) {
    SCOPED_TRACE(g.name);
    const mg::MedialSurface s = g.make();
    std::set<std::pair<int, int>> edges;
    for (const auto& e : s.edges) EXPECT_TRUE(edges.insert(key(e[0], e[1])).second);
    std::set<std::array<int, 3>> faces;
    for (auto f : s.faces) {
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(edges.count(key(f[k], f[(k + 1) % 3])));
      std::sort(f.begin(), f.end());
      EXPECT_TRUE(faces.insert(f).second);
    }
    const int euler = static_cast<int>(s.atoms.size()) - static_cast<int>(s.edges.size()) +
                      static_cast<int>(s.faces.size());
    EXPECT_EQ(euler, g.euler);
  }
}

TEST(MedialShapes, DeterministicAndExactThroughTheMaFormat) {
  for (const Generator& g : generators()) {
    SCOPED_TRACE(g.name);
    std::ostringstream first, second;
    mg::format_medial_surface(first, g.make());
    mg::format_medial_surface(second, g.make());
    EXPECT_EQ(first.str(), second.str());
    std::istringstream in(first.str());
    const mg::MedialSurface back = mg::parse_medial_surface(in, g.name + ".ma");
    const mg::MedialSurface s = g.make();
    ASSERT_EQ(back.atoms.size(), s.atoms.size());
    for (std::size_t i = 0; i < s.atoms.size(); ++i) {
      EXPECT_EQ(back.atoms[i].centre, s.atoms[i].centre);
      EXPECT_EQ(back.atoms[i].radius, s.atoms[i].radius);
    }
    EXPECT_EQ(back.edges, s.edges);
    EXPECT_EQ(back.faces, s.faces);
  }
}

TEST(MedialShapes, CapsuleBallsAreDisjointAndUnequal) {
  const auto s = mg::make_medial_capsule();
  EXPECT_GT(ball_gap(s, 0, 1), 0.1);
  EXPECT_NE(s.atoms[0].radius, s.atoms[1].radius);
}

TEST(MedialShapes, SlabBallsAreDisjointWithDifferentRadii) {
  const auto s = mg::make_medial_slab();
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      EXPECT_GT(ball_gap(s, i, j), 0.1);
      EXPECT_NE(s.atoms[i].radius, s.atoms[j].radius);
    }
  const auto& a = s.atoms;
  const Vector3d n = (a[1].centre - a[0].centre).cross(a[2].centre - a[0].centre);
  EXPECT_GT(n.norm(), 0.5);  // far from collinear
}

TEST(MedialShapes, RingKeepsItsHoleOpen) {
  for (int n : {3, 16, 64}) {
    SCOPED_TRACE(n);
    const auto s = mg::make_medial_ring(n);
    ASSERT_EQ(s.atoms.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(s.edges.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(components(s), 1u);
    // Each edge's cone (inside the capsule of its larger radius) keeps clear of the z axis (a
    // segment on it, long enough): by 0.25 always, by 0.7 from 8 atoms on.
    const Vector3d lo(0, 0, -10), hi(0, 0, 10);
    for (const auto& e : s.edges) {
      const double r = std::max(s.atoms[e[0]].radius, s.atoms[e[1]].radius);
      const double clearance =
          segment_distance(s.atoms[e[0]].centre, s.atoms[e[1]].centre, lo, hi) - r;
      EXPECT_GT(clearance, n >= 8 ? 0.7 : 0.25);
      EXPECT_EQ((e[1] - e[0] + n) % n, 1);  // a cycle through the atoms in order
    }
  }
  // The default ring mixes overlapping and disjoint neighbours, and edges two apart along the
  // ring keep clear of each other where the balls are small.
  const auto s = mg::make_medial_ring();
  int overlapping = 0, disjoint = 0;
  for (const auto& e : s.edges) (ball_gap(s, e[0], e[1]) < 0 ? overlapping : disjoint)++;
  EXPECT_GT(overlapping, 2);
  EXPECT_GT(disjoint, 2);
  double largest_gap = -1;
  for (int k = 0; k < 16; ++k)
    largest_gap = std::max(largest_gap, cone_gap(s, s.edges[k], s.edges[(k + 2) % 16]));
  EXPECT_GT(largest_gap, 0);
}

TEST(MedialShapes, DiscSizesFollowTheHexagon) {
  for (int rings = 1; rings <= 5; ++rings) {
    SCOPED_TRACE(rings);
    const auto s = mg::make_medial_disc(rings);
    EXPECT_NO_THROW(mg::validate(s));
    EXPECT_EQ(s.atoms.size(), static_cast<std::size_t>(3 * rings * rings + 3 * rings + 1));
    EXPECT_EQ(s.edges.size(), static_cast<std::size_t>(9 * rings * rings + 3 * rings));
    EXPECT_EQ(s.faces.size(), static_cast<std::size_t>(6 * rings * rings));
    EXPECT_EQ(components(s), 1u);
  }
}

TEST(MedialShapes, DiscIsCurvedAndThinsTowardTheRim) {
  const auto s = mg::make_medial_disc();
  auto rho = [&](int i) { return s.atoms[i].centre.head<2>().norm(); };
  // Along every edge the atom farther from the axis is the thinner one.
  for (const auto& e : s.edges) {
    if (std::abs(rho(e[0]) - rho(e[1])) < 1e-9) continue;
    const int outer = rho(e[0]) > rho(e[1]) ? e[0] : e[1];
    const int inner = e[0] + e[1] - outer;
    EXPECT_LT(s.atoms[outer].radius, s.atoms[inner].radius);
  }
  // The centre atom is the largest ball.
  const auto largest = std::max_element(s.atoms.begin(), s.atoms.end(),
                                        [](auto& a, auto& b) { return a.radius < b.radius; });
  EXPECT_LT(largest->centre.norm(), 1e-12);
  // Not planar: face normals (CCW seen from +z) turn by over 10 degrees across the disc.
  double min_cos = 1;
  for (const auto& f : s.faces) {
    const Vector3d n = (s.atoms[f[1]].centre - s.atoms[f[0]].centre)
                           .cross(s.atoms[f[2]].centre - s.atoms[f[0]].centre)
                           .normalized();
    EXPECT_GT(n.z(), 0);
    min_cos = std::min(min_cos, n.z());
  }
  EXPECT_LT(min_cos, std::cos(10 * M_PI / 180));
  // Neighbours overlap near the centre and are disjoint at the rim.
  int overlapping = 0, disjoint = 0;
  for (const auto& e : s.edges) (ball_gap(s, e[0], e[1]) < 0 ? overlapping : disjoint)++;
  EXPECT_GT(overlapping, 0);
  EXPECT_GT(disjoint, 0);
}

TEST(MedialShapes, SheetsMeetAlongOneEdge) {
  const auto s = mg::make_medial_sheets();
  std::map<std::pair<int, int>, int> faces_at;
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k) ++faces_at[key(f[k], f[(k + 1) % 3])];
  int non_manifold = 0;
  for (const auto& [edge, count] : faces_at) {
    EXPECT_LE(count, 3);
    if (count == 3) {
      ++non_manifold;
      EXPECT_EQ(edge, key(0, 1));
    }
  }
  EXPECT_EQ(non_manifold, 1);
  // Removing the spine leaves three separate sheets.
  mg::UnionFind u(s.atoms.size());
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k)
      if (f[k] > 1 && f[(k + 1) % 3] > 1) u.unite(f[k], f[(k + 1) % 3]);
  std::set<std::size_t> sheets;
  for (std::size_t i = 2; i < s.atoms.size(); ++i) sheets.insert(u.find(i));
  EXPECT_EQ(sheets.size(), 3u);
}

/// The hand's fingers: each a chain of the atoms in no face, with the edge joining it to the
/// palm; listed as their edges, from the palm outward.
std::vector<std::vector<Edge>> fingers(const mg::MedialSurface& s) {
  std::vector<bool> palm(s.atoms.size(), false);
  for (const auto& f : s.faces)
    for (int i : f) palm[i] = true;
  std::vector<std::vector<Edge>> out;
  for (const auto& e : s.edges) {
    if (palm[e[0]] == palm[e[1]]) continue;
    // A link from the palm: follow the chain.
    std::vector<Edge> chain = {palm[e[0]] ? e : Edge{e[1], e[0]}};
    for (bool extended = true; extended;) {
      extended = false;
      for (const auto& next : s.edges) {
        const int tip = chain.back()[1];
        const int back = chain.back()[0];
        if (next[0] == tip && next[1] != back && !palm[next[1]])
          chain.push_back(next), extended = true;
        else if (next[1] == tip && next[0] != back && !palm[next[0]])
          chain.push_back({next[1], next[0]}), extended = true;
        if (extended) break;
      }
    }
    out.push_back(chain);
  }
  return out;
}

TEST(MedialShapes, HandHasAPalmAndFiveSeparateFingers) {
  const auto s = mg::make_medial_hand();
  const auto all = fingers(s);
  ASSERT_EQ(all.size(), 5u);
  std::multiset<std::size_t> lengths;
  std::size_t finger_atoms = 0;
  for (const auto& f : all) {
    lengths.insert(f.size());
    finger_atoms += f.size();
    // Radii decrease from the palm outward.
    for (const auto& e : f) EXPECT_LT(s.atoms[e[1]].radius, s.atoms[e[0]].radius);
  }
  EXPECT_EQ(lengths, (std::multiset<std::size_t>{3, 3, 4, 4, 4}));
  // Every atom is in the palm or in one finger.
  std::set<int> palm;
  for (const auto& f : s.faces) palm.insert(f.begin(), f.end());
  EXPECT_EQ(palm.size() + finger_atoms, s.atoms.size());
  // No two fingers touch: the cones of their edges (the links to the palm included) are
  // disjoint, with room to spare.
  double closest = 1e9;
  for (std::size_t a = 0; a < all.size(); ++a)
    for (std::size_t b = a + 1; b < all.size(); ++b)
      for (const auto& ea : all[a])
        for (const auto& eb : all[b]) closest = std::min(closest, cone_gap(s, ea, eb));
  EXPECT_GT(closest, 0.04 - 1e-9);
  // Past its first atom, no finger comes near the cones of the palm's edges.
  double palm_gap = 1e9;
  for (const auto& f : all)
    for (std::size_t k = 1; k < f.size(); ++k)
      for (const auto& e : s.edges)
        if (palm.count(e[0]) && palm.count(e[1]))
          palm_gap = std::min(palm_gap, cone_gap(s, f[k], e));
  EXPECT_GT(palm_gap, 0.04 - 1e-9);
}

TEST(MedialShapes, PreconditionsAreChecked) {
  EXPECT_THROW(mg::make_medial_ring(2), mg::InvalidInput);
  EXPECT_THROW(mg::make_medial_disc(0), mg::InvalidInput);
  EXPECT_THROW(mg::make_medial_disc(101), mg::InvalidInput);
}

}  // namespace
