// The distance core (distances.h) and its mesh front end (mesh_distance.h).
#include "evaluate/distances.h"
#include "core/errors.h"
#include "core/shapes.h"
#include "evaluate/mesh_distance.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

namespace ev = mg::evaluate;

namespace {

/// The unit cube [0, 1]^3 as 12 triangles, CCW from outside.
mg::PolygonSoup unit_cube() {
  mg::PolygonSoup box = mg::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  mg::PolygonSoup t;
  t.points = box.points;
  for (const auto& f : box.faces) {
    t.faces.push_back({f[0], f[1], f[2]});
    t.faces.push_back({f[0], f[2], f[3]});
  }
  return t;
}

ev::MeshDistanceOptions with_samples(std::size_t n) {
  ev::MeshDistanceOptions opt;
  opt.samples = n;
  return opt;
}

}  // namespace

TEST(Distances, ConcentricSpheresAreTheirRadiusDifferenceApart) {
  const mg::PolygonSoup inner = mg::make_geodesic_sphere(32, 1.0);
  const mg::PolygonSoup outer = mg::make_geodesic_sphere(32, 1.1);
  const ev::MeshDistance r = ev::mesh_distance(inner, outer, with_samples(200000));
  EXPECT_NEAR(r.distance.hausdorff, 0.1, 0.001);
  EXPECT_NEAR(r.distance.rms, 0.1, 0.001);
  EXPECT_NEAR(r.distance.mean, 0.1, 0.001);
  EXPECT_NEAR(r.diagonal, 2 * std::sqrt(3.0) * 1.1, 1e-9);
  EXPECT_EQ(r.samples, 200000u);
  EXPECT_EQ(r.distance.a_to_b.samples, 200000u);
}

TEST(Distances, AMeshAgainstItselfIsZero) {
  const mg::PolygonSoup torus = mg::make_bumpy_torus(60, 30, 1.0, 0.3, 0.1, 6, 3);
  const ev::MeshDistance r = ev::mesh_distance(torus, torus, with_samples(100000));
  EXPECT_LT(r.distance.hausdorff, 1e-12);
  EXPECT_LT(r.distance.rms, 1e-12);
}

TEST(Distances, PushingOneCubeVertexOutSeparatesTheOneSidedValues) {
  const mg::PolygonSoup cube = unit_cube();
  mg::PolygonSoup pushed = cube;
  int corner = -1;
  for (std::size_t i = 0; i < pushed.points.size(); ++i)
    if (pushed.points[i].isApprox(Eigen::Vector3d::Ones())) corner = static_cast<int>(i);
  ASSERT_GE(corner, 0);
  pushed.points[corner] += 0.2 * Eigen::Vector3d::Ones().normalized();

  const ev::MeshDistance r = ev::mesh_distance(cube, pushed, with_samples(100000));
  // pushed -> cube: the moved vertex is a sample and the cube's corner is its closest point.
  EXPECT_NEAR(r.distance.b_to_a.max, 0.2, 1e-9);
  EXPECT_TRUE(r.distance.b_to_a.farthest.isApprox(pushed.points[corner], 1e-12));
  // cube -> pushed: the cube's corner (a sample) is inside the bump, nearer to its tilted
  // triangles than 0.2; nothing on the cube is farther from the pushed mesh than that corner.
  const ev::TriangleIndex pushed_index(pushed);
  double corner_distance = 0;
  const Eigen::Vector3d one = Eigen::Vector3d::Ones();
  pushed_index.distances(&one, 1, &corner_distance);
  EXPECT_LT(corner_distance, 0.15);
  EXPECT_NEAR(r.distance.a_to_b.max, corner_distance, 1e-9);
  EXPECT_DOUBLE_EQ(r.distance.hausdorff, r.distance.b_to_a.max);
  EXPECT_GT(r.distance.b_to_a.rms, 0.0);
}

TEST(Distances, DoublingTheDefaultSampleCountMovesHausdorffByUnderOnePercent) {
  const mg::PolygonSoup a = mg::make_bumpy_torus(120, 60, 1.0, 0.3, 0.05, 6, 3);
  const mg::PolygonSoup b = mg::make_bumpy_torus(100, 50, 1.0, 0.3, 0.05, 6, 3);
  const std::size_t n = ev::default_sample_count(a, b);
  EXPECT_EQ(n, 1000000u);
  const ev::MeshDistance once = ev::mesh_distance(a, b, with_samples(n));
  const ev::MeshDistance twice = ev::mesh_distance(a, b, with_samples(2 * n));
  ASSERT_GT(once.distance.hausdorff, 0.0);
  EXPECT_LT(std::abs(twice.distance.hausdorff / once.distance.hausdorff - 1), 0.01);
  EXPECT_LT(std::abs(twice.distance.rms / once.distance.rms - 1), 0.01);
}

TEST(Distances, DefaultSampleCountGrowsWithTheVertices) {
  const mg::PolygonSoup big = mg::make_torus(400, 200, 1.0, 0.3);  // 80k vertices
  EXPECT_EQ(ev::default_sample_count(big, big), 10u * 2 * 80000);
}

TEST(Distances, SameResultAtOneAndTwoThreads) {
  const mg::PolygonSoup a = mg::make_geodesic_sphere(20, 1.0);
  const mg::PolygonSoup b = mg::make_bumpy_torus(60, 30, 1.0, 0.3, 0.1, 6, 3);
  ev::MeshDistance one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = ev::mesh_distance(a, b, with_samples(50000));
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = ev::mesh_distance(a, b, with_samples(50000));
  }
  EXPECT_EQ(one.distance.hausdorff, two.distance.hausdorff);
  EXPECT_EQ(one.distance.a_to_b.rms, two.distance.a_to_b.rms);
  EXPECT_EQ(one.distance.b_to_a.mean, two.distance.b_to_a.mean);
}

TEST(Distances, MetroSamplingTakesEveryVertexAndWeighsOnlyFacePoints) {
  const mg::PolygonSoup cube = unit_cube();
  ev::SamplingOptions opt;
  opt.count = 1000;
  const ev::SurfaceSamples s = ev::sample_surface(cube, opt, "cube");
  ASSERT_EQ(s.points.size(), 1000u);
  const std::size_t edge_points = (1000 - 8) / 4;
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_TRUE(s.points[i].isApprox(cube.points[i]));
    EXPECT_EQ(s.weights[i], 0.0);
  }
  for (std::size_t i = 8; i < 8 + edge_points; ++i) {
    // On one of the triangles' edges: a cube edge (two coordinates in {0, 1}) or a face
    // diagonal (one coordinate in {0, 1}, the other two equal or summing to 1).
    const Eigen::Vector3d& p = s.points[i];
    std::vector<double> free;
    for (int k = 0; k < 3; ++k)
      if (std::abs(p[k]) > 1e-12 && std::abs(p[k] - 1) > 1e-12) free.push_back(p[k]);
    const bool on_edge =
        free.size() <= 1 || (free.size() == 2 && (std::abs(free[0] - free[1]) < 1e-12 ||
                                                  std::abs(free[0] + free[1] - 1) < 1e-12));
    EXPECT_TRUE(on_edge) << p.transpose();
    EXPECT_EQ(s.weights[i], 0.0);
  }
  // Face points: on the surface, weight 1, about equally many on each of the 6 faces.
  std::array<int, 6> per_face{};
  for (std::size_t i = 8 + edge_points; i < s.points.size(); ++i) {
    EXPECT_EQ(s.weights[i], 1.0);
    const Eigen::Vector3d& p = s.points[i];
    int face = -1;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(p[k]) < 1e-12) face = 2 * k;
      if (std::abs(p[k] - 1) < 1e-12) face = 2 * k + 1;
    }
    ASSERT_GE(face, 0) << p.transpose();
    ++per_face[face];
  }
  const double expected = (1000.0 - 8 - edge_points) / 6;
  for (int n : per_face) EXPECT_LE(std::abs(n - expected), 1.0);
}

TEST(Distances, FaceOnlySamplingIsAreaUniform) {
  // Two triangles of areas 1 and 3: systematic sampling gives them 1/4 and 3/4 of the points.
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {10, 0, 0}, {13, 0, 0}, {10, 2, 0}};
  soup.faces = {{0, 1, 2}, {3, 4, 5}};
  ev::SamplingOptions opt;
  opt.count = 4000;
  opt.vertices_and_edges = false;
  const ev::SurfaceSamples s = ev::sample_surface(soup, opt, "two");
  ASSERT_EQ(s.points.size(), 4000u);
  const auto small = std::count_if(s.points.begin(), s.points.end(),
                                   [](const Eigen::Vector3d& p) { return p.x() < 5; });
  EXPECT_EQ(small, 1000);
  for (const auto& p : s.points) {
    const Eigen::Vector3d q = p.x() < 5 ? p : Eigen::Vector3d((p.x() - 10) / 3, p.y(), p.z());
    EXPECT_GE(q.x(), -1e-12);
    EXPECT_GE(q.y(), -1e-12);
    EXPECT_LE(q.x() + q.y() / 2, 1 + 1e-12);
  }
}

TEST(Distances, TheCoreTakesAnyOracleAndWeights) {
  // Samples on a sphere of radius 1.1 against the exact unit sphere: the core does not care
  // where distances come from (this is how `evaluate atoms` plugs in point-to-G distances).
  ev::SurfaceSamples s;
  for (int i = 0; i < 100; ++i) {
    const double t = 0.1 * i;
    s.points.push_back(1.1 * Eigen::Vector3d(std::cos(t), std::sin(t), 0));
    s.weights.push_back(1.0);
  }
  s.points.push_back({3, 0, 0});  // weight 0: changes the max only
  s.weights.push_back(0.0);
  const ev::DistanceOracle unit_sphere = [](const Eigen::Vector3d* p, std::size_t n, double* d) {
    for (std::size_t i = 0; i < n; ++i) d[i] = std::abs(p[i].norm() - 1);
  };
  const ev::OneSidedDistance r = ev::one_sided_distance(s, unit_sphere);
  EXPECT_NEAR(r.max, 2.0, 1e-15);
  EXPECT_NEAR(r.mean, 0.1, 1e-12);
  EXPECT_NEAR(r.rms, 0.1, 1e-12);
  EXPECT_EQ(r.samples, 101u);
  EXPECT_EQ(r.weighted_samples, 100u);
  EXPECT_TRUE(r.farthest.isApprox(Eigen::Vector3d(3, 0, 0)));

  // Weighted: distances 1 (weight 3) and 2 (weight 1) -> mean 1.25, rms sqrt(7/4).
  ev::SurfaceSamples w;
  w.points = {{2, 0, 0}, {3, 0, 0}};
  w.weights = {3.0, 1.0};
  const ev::OneSidedDistance rw = ev::one_sided_distance(w, unit_sphere);
  EXPECT_NEAR(rw.mean, 1.25, 1e-15);
  EXPECT_NEAR(rw.rms, std::sqrt(7.0 / 4), 1e-15);

  const ev::TwoSidedDistance two = ev::two_sided_distance(s, unit_sphere, w, unit_sphere);
  EXPECT_EQ(two.hausdorff, 2.0);
  EXPECT_EQ(two.mean, 1.25);
}

TEST(Distances, BadInputIsRefused) {
  const ev::DistanceOracle zero = [](const Eigen::Vector3d*, std::size_t n, double* d) {
    std::fill(d, d + n, 0.0);
  };
  EXPECT_THROW(ev::one_sided_distance({}, zero), mg::InvalidInput);
  ev::SurfaceSamples s;
  s.points = {{0, 0, 0}};
  EXPECT_THROW(ev::one_sided_distance(s, zero), mg::InvalidInput);  // no weight
  s.weights = {0.0};
  EXPECT_THROW(ev::one_sided_distance(s, zero), mg::InvalidInput);  // weights sum to 0
  s.weights = {std::nan("")};
  EXPECT_THROW(ev::one_sided_distance(s, zero), mg::InvalidInput);
  s.weights = {1.0};
  const ev::DistanceOracle broken = [](const Eigen::Vector3d*, std::size_t n, double* d) {
    std::fill(d, d + n, -1.0);
  };
  EXPECT_THROW(ev::one_sided_distance(s, broken), mg::NumericalError);

  mg::PolygonSoup flat;
  flat.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.faces = {{0, 1, 2}};
  EXPECT_THROW(ev::sample_surface(flat, {}, "flat"), mg::InvalidInput);
  EXPECT_THROW(ev::TriangleIndex{flat}, mg::InvalidInput);

  const mg::PolygonSoup sphere = mg::make_geodesic_sphere(10);  // 1002 vertices
  ev::SamplingOptions few;
  few.count = 1500;
  EXPECT_THROW(ev::sample_surface(sphere, few, "sphere"), mg::InvalidInput);
  few.vertices_and_edges = false;
  EXPECT_EQ(ev::sample_surface(sphere, few, "sphere").points.size(), 1500u);
  few.count = 0;
  EXPECT_THROW(ev::sample_surface(sphere, few, "sphere"), mg::InvalidInput);
  EXPECT_THROW(ev::percent_of_diagonal(1, 0), mg::InvalidInput);
}
