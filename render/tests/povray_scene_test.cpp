#include "render/povray_scene.h"

#include "core/errors.h"
#include "core/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>

#include "test_util.h"

namespace {

using mg::render::SceneObject;

SceneObject sphere_object() {
  return {"sphere", mg::make_geodesic_sphere(/*frequency=*/3, /*radius=*/1.0)};
}

SceneObject two_atoms() {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(-1, 0, 0), 0.25}, {Eigen::Vector3d(1, 0, 0), 0.75}};
  return {"atoms", s};
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// The text between `open` (included) and the first "}\n" line after it.
std::string block(const std::string& text, const std::string& open) {
  const auto begin = text.find(open);
  if (begin == std::string::npos) return {};
  return text.substr(begin, text.find("\n}\n", begin) + 3 - begin);
}

/// "x, y, z" as a vector.
Eigen::Vector3d vector_of(const std::string& text) {
  Eigen::Vector3d v;
  char comma;
  std::istringstream(text) >> v.x() >> comma >> v.y() >> comma >> v.z();
  return v;
}

/// Every number in `text` (its identifiers hold none: only lists of numbers and vectors).
std::vector<double> numbers_in(const std::string& text) {
  static const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
  std::vector<double> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number);
       it != std::sregex_iterator(); ++it)
    out.push_back(std::stod(it->str()));
  return out;
}

/// The text between `open` and `close` (both excluded), after `open`'s first occurrence.
std::string between(const std::string& text, const std::string& open, const std::string& close) {
  const auto begin = text.find(open);
  if (begin == std::string::npos) return {};
  const auto from = begin + open.size();
  return text.substr(from, text.find(close, from) - from);
}

/// The cones of a scene: base centre, base radius, cap centre, cap radius.
struct ConeText {
  Eigen::Vector3d base, cap;
  double r_base, r_cap;
  std::string rest;  ///< the rest of the line: "open texture { ... }"
};

std::vector<ConeText> cones_in(const std::string& scene) {
  static const std::regex cone(R"(\ncone \{ <([^>]*)>, (\S+), <([^>]*)>, (\S+) ([^\n]*))");
  std::vector<ConeText> out;
  for (auto it = std::sregex_iterator(scene.begin(), scene.end(), cone);
       it != std::sregex_iterator(); ++it)
    out.push_back({vector_of((*it)[1]), vector_of((*it)[3]), std::stod((*it)[2]),
                   std::stod((*it)[4]), (*it)[5]});
  return out;
}

/// The slabs' mesh2 of a scene: vertices, triangles, and each triangle's corner colours
/// (linear RGB, read from the texture list and the level textures it names).
struct Mesh2Text {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<Eigen::Vector3d, 3>> colours;
};

Mesh2Text mesh2_in(const std::string& scene) {
  Mesh2Text m;
  const std::vector<double> v = numbers_in(between(scene, "vertex_vectors { ", "}"));
  for (std::size_t i = 1; i + 2 < v.size(); i += 3)
    m.vertices.emplace_back(v[i], v[i + 1], v[i + 2]);
  EXPECT_EQ(v.empty() ? -1.0 : v[0], static_cast<double>(m.vertices.size()));
  std::vector<Eigen::Vector3d> palette;  // the texture list's colours
  const std::string list = between(scene, "texture_list { ", "face_indices");
  static const std::regex entry(R"(texture \{ (mg_atoms0_(\d+)|pigment \{ rgb <([^>]*)>))");
  for (auto it = std::sregex_iterator(list.begin(), list.end(), entry);
       it != std::sregex_iterator(); ++it) {
    const std::string colour =
        (*it)[2].matched
            ? between(scene,
                      "#declare mg_atoms0_" + (*it)[2].str() + " = texture { pigment { rgb <", ">")
            : (*it)[3].str();
    palette.push_back(vector_of(colour));
  }
  const std::vector<double> f = numbers_in(between(scene, "face_indices { ", "}"));
  for (std::size_t i = 1; i + 5 < f.size(); i += 6) {
    m.triangles.push_back(
        {static_cast<int>(f[i]), static_cast<int>(f[i + 1]), static_cast<int>(f[i + 2])});
    m.colours.push_back({palette.at(static_cast<std::size_t>(f[i + 3])),
                         palette.at(static_cast<std::size_t>(f[i + 4])),
                         palette.at(static_cast<std::size_t>(f[i + 5]))});
  }
  EXPECT_EQ(f.empty() ? -1.0 : f[0], static_cast<double>(m.triangles.size()));
  return m;
}

/// The colour value of an atom's radius as the scene quantises it (256 levels).
double level_value(double r, double lo, double hi) {
  return std::lround((r - lo) / (hi - lo) * 255) / 255.0;
}

TEST(RadiusColour, HotForSmallColdForLarge) {
  EXPECT_EQ(mg::render::radius_colour(0.0), Eigen::Vector3d(1, 0, 0));   // red
  EXPECT_EQ(mg::render::radius_colour(0.25), Eigen::Vector3d(1, 1, 0));  // yellow
  EXPECT_EQ(mg::render::radius_colour(0.5), Eigen::Vector3d(0, 1, 0));   // green
  EXPECT_EQ(mg::render::radius_colour(1.0), Eigen::Vector3d(0, 0, 1));   // blue
  EXPECT_EQ(mg::render::radius_colour(-3.0), Eigen::Vector3d(1, 0, 0));  // clamped
  // HSV: full saturation and value, hue = 240 degrees * t.
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 100.0;
    const Eigen::Vector3d c = mg::render::radius_colour(t);
    const double hi = c.maxCoeff(), lo = c.minCoeff();
    EXPECT_EQ(hi, 1.0);
    EXPECT_EQ(lo, 0.0);
    double hue = c.x() == hi   ? 60 * (c.y() - c.z())
                 : c.y() == hi ? 60 * (c.z() - c.x() + 2)
                               : 60 * (c.x() - c.y() + 4);
    if (hue < 0) hue += 360;
    EXPECT_NEAR(hue, 240 * t, 1e-9) << t;
  }
}

TEST(PovrayScene, MeshBecomesSmoothMesh2) {
  const SceneObject sphere = sphere_object();
  const auto& soup = std::get<mg::PolygonSoup>(sphere.geometry);
  const auto view = mg::render::frame_view(mg::render::bounding_box(sphere), 160, 120);
  const std::string scene = mg::render::povray_scene({sphere}, view);
  EXPECT_EQ(count(scene, "mesh2 {"), 1u);
  EXPECT_NE(scene.find("vertex_vectors { " + std::to_string(soup.points.size()) + ","),
            std::string::npos);
  EXPECT_NE(scene.find("normal_vectors { " + std::to_string(soup.points.size()) + ","),
            std::string::npos);
  EXPECT_NE(scene.find("face_indices { " + std::to_string(soup.faces.size()) + ","),
            std::string::npos);
  EXPECT_EQ(scene.find("normal_indices"), std::string::npos);  // one normal per vertex
  EXPECT_NE(scene.find("#version 3.7;"), std::string::npos);
  EXPECT_NE(scene.find("background { rgb <1, 1, 1> }"), std::string::npos);
  EXPECT_EQ(count(scene, "light_source {"), 3u);
  // Deterministic text.
  EXPECT_EQ(scene, mg::render::povray_scene({sphere}, view));

  mg::render::SceneOptions flat;
  flat.flat_shading = true;
  EXPECT_EQ(mg::render::povray_scene({sphere}, view, flat).find("normal_vectors"),
            std::string::npos);
  mg::render::SceneOptions creased;
  creased.normals.crease_angle = 5;  // sharper than the sphere's facets: every corner differs
  EXPECT_NE(mg::render::povray_scene({sphere}, view, creased).find("normal_indices"),
            std::string::npos);
}

TEST(PovrayScene, PolygonsAreFanTriangulated) {
  const SceneObject box{"box", mg::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3))};
  const auto view = mg::render::frame_view(mg::render::bounding_box(box), 100, 100);
  const std::string scene = mg::render::povray_scene({box}, view);
  EXPECT_NE(scene.find("face_indices { 12,"), std::string::npos);
  // By default the box's 90-degree edges are creases: corners take their face's normal.
  EXPECT_NE(scene.find("normal_vectors { 32,"), std::string::npos);
  EXPECT_NE(scene.find("normal_indices { 12,"), std::string::npos);
  mg::render::SceneOptions smooth;
  smooth.normals.crease_angle = 180;
  EXPECT_EQ(mg::render::povray_scene({box}, view, smooth).find("normal_indices"),
            std::string::npos);
}

TEST(PovrayScene, AtomsAreSpheresColouredByRadius) {
  const SceneObject atoms = two_atoms();
  const auto view = mg::render::frame_view(mg::render::bounding_box(atoms), 160, 120);
  const std::string scene = mg::render::povray_scene({atoms}, view);
  EXPECT_EQ(count(scene, "\nsphere { "), 2u);
  // The small atom uses the red texture (level 0), the large one the blue one (last level).
  EXPECT_NE(scene.find("sphere { <-1, 0, 0>, 0.25 texture { mg_atoms0_0 } }"), std::string::npos);
  EXPECT_NE(scene.find("sphere { <1, 0, 0>, 0.75 texture { mg_atoms0_255 } }"), std::string::npos);
  EXPECT_NE(scene.find("#declare mg_atoms0_0 = texture { pigment { rgb <1, 0, 0> }"),
            std::string::npos);
  EXPECT_NE(scene.find("#declare mg_atoms0_255 = texture { pigment { rgb <0, 0, 1> }"),
            std::string::npos);
  EXPECT_EQ(count(scene, "#declare mg_atoms0_"), 2u);  // only used levels are declared
}

TEST(PovrayScene, CapsuleConeSpansTheTangentCircles) {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(0, 0, 0), 1.0}, {Eigen::Vector3d(4, 0, 0), 0.5}};
  s.edges = {{0, 1}};
  const SceneObject capsule{"capsule", s};
  const auto view = mg::render::frame_object(capsule, 160, 120);
  const std::string scene = mg::render::povray_scene({capsule}, view);
  EXPECT_EQ(count(scene, "\nsphere { "), 2u);
  const std::vector<ConeText> cones = cones_in(scene);
  ASSERT_EQ(cones.size(), 1u);
  // The lateral surface runs between the tangent circles: sin(phi) = (r1 - r2) / L.
  const double sin_phi = (1.0 - 0.5) / 4, cos_phi = std::sqrt(1 - sin_phi * sin_phi);
  const ConeText& k = cones[0];
  EXPECT_LT((k.base - Eigen::Vector3d(1.0 * sin_phi, 0, 0)).norm(), 1e-12);
  EXPECT_LT((k.cap - Eigen::Vector3d(4 + 0.5 * sin_phi, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(k.r_base, 1.0 * cos_phi, 1e-12);
  EXPECT_NEAR(k.r_cap, 0.5 * cos_phi, 1e-12);
  // Each rim lies on its ball's sphere (the cone is tangent to it there).
  EXPECT_NEAR(std::hypot(k.base.x(), k.r_base), 1.0, 1e-12);
  EXPECT_NEAR(std::hypot(k.cap.x() - 4, k.r_cap), 0.5, 1e-12);
  // Coloured along the axis from blue (r = 1, the base) to red (r = 0.5, the cap) through the
  // hue breaks, where the touching ball's radius is 7/8, 3/4 and 5/8: a quarter of the way each.
  EXPECT_NE(k.rest.find("gradient <1, 0, 0> color_map { [0.25 mg_atoms0_rgb255] [0.375 rgb <0, "
                        "1, 1>] [0.5 rgb <0, 1, 0>] [0.625 rgb <1, 1, 0>] [0.75 mg_atoms0_rgb0] }"),
            std::string::npos)
      << k.rest;
  EXPECT_NE(scene.find("#declare mg_atoms0_rgb255 = rgb <0, 0, 1>;"), std::string::npos);
  // The pattern value (P - translate) . u / scale is 0.25 at the base and 0.75 at the cap.
  const double scale = std::stod(between(k.rest, " scale ", " "));
  const Eigen::Vector3d shift = vector_of(between(k.rest, " translate <", ">"));
  EXPECT_NEAR((k.base - shift).x() / scale, 0.25, 1e-12);
  EXPECT_NEAR((k.cap - shift).x() / scale, 0.75, 1e-12);
  // The camera frames the balls, which hold the cone: its rims lie in their box.
  const Eigen::AlignedBox3d box = mg::render::bounding_box(capsule);
  for (const auto& [c, r] : {std::pair{k.base, k.r_base}, std::pair{k.cap, k.r_cap}})
    EXPECT_TRUE(box.contains(
        Eigen::AlignedBox3d(c - Eigen::Vector3d(0, r, r), c + Eigen::Vector3d(0, r, r))));
}

TEST(PovrayScene, FaceAddsItsTwoTangentTrianglesColouredByRadius) {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(0, 0, 0), 0.5},
             {Eigen::Vector3d(2, 0, 0), 0.35},
             {Eigen::Vector3d(0.8, 1.6, 0.3), 0.25}};
  s.faces = {{0, 1, 2}};
  const SceneObject face{"face", s};
  const auto view = mg::render::frame_object(face, 160, 120);
  const std::string scene = mg::render::povray_scene({face}, view);
  EXPECT_EQ(count(scene, "\nsphere { "), 3u);
  EXPECT_EQ(cones_in(scene).size(), 3u);  // the face's sides are edges
  EXPECT_EQ(count(scene, "mesh2 {"), 1u);
  const Mesh2Text m = mesh2_in(scene);
  // The corners of the tangent triangles: for each atom, the two vertices at distance r from
  // its centre, one per triangle.
  std::array<std::vector<Eigen::Vector3d>, 3> touch;
  for (const auto& v : m.vertices)
    for (int i = 0; i < 3; ++i)
      if (std::abs((v - s.atoms[i].centre).norm() - s.atoms[i].radius) < 1e-12)
        touch[i].push_back(v);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(touch[i].size(), 2u) << "atom " << i;
  // Matched by their unit normal n = (t - c) / r, each triangle lies in a plane tangent to the
  // three balls: n . t_i is the same for its three corners.
  std::array<std::array<Eigen::Vector3d, 3>, 2> tangent;
  std::array<Eigen::Vector3d, 2> normal;
  for (int side = 0; side < 2; ++side) {
    normal[side] = (touch[0][side] - s.atoms[0].centre) / s.atoms[0].radius;
    tangent[side][0] = touch[0][side];
    for (int i = 1; i < 3; ++i) {
      int found = 0;
      for (const auto& t : touch[i])
        if (((t - s.atoms[i].centre) / s.atoms[i].radius - normal[side]).norm() < 1e-9) {
          tangent[side][i] = t;
          ++found;
        }
      ASSERT_EQ(found, 1) << "side " << side << ", atom " << i;
      EXPECT_NEAR(normal[side].dot(tangent[side][i]), normal[side].dot(tangent[side][0]), 1e-12);
    }
  }
  EXPECT_GT((normal[0] - normal[1]).norm(), 0.1);
  // The mesh tiles the two triangles: each piece lies in one of them and their areas add up.
  const double lo = 0.25, hi = 0.5;
  std::array<double, 2> area = {0, 0};
  const Eigen::AlignedBox3d box = mg::render::bounding_box(face);
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const auto& t = m.triangles[f];
    const Eigen::Vector3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    int side = -1;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector3d& t0 = tangent[k][0];
      const Eigen::Vector3d nk = (tangent[k][1] - t0).cross(tangent[k][2] - t0);
      // Barycentric coordinates of every corner in triangle k, all in [0, 1] if it lies there.
      bool inside = true;
      for (const Eigen::Vector3d* p : {&a, &b, &c}) {
        const double l1 = (*p - t0).cross(tangent[k][2] - t0).dot(nk) / nk.squaredNorm();
        const double l2 = (tangent[k][1] - t0).cross(*p - t0).dot(nk) / nk.squaredNorm();
        const double l0 = 1 - l1 - l2;
        const bool in_plane = std::abs((*p - t0).dot(nk.normalized())) < 1e-12;
        inside = inside && in_plane && l0 > -1e-12 && l1 > -1e-12 && l2 > -1e-12;
      }
      if (inside) side = k;
    }
    ASSERT_GE(side, 0) << "triangle " << f << " lies in neither tangent triangle";
    area[side] += (b - a).cross(c - a).norm() / 2;
    // Each corner's colour is radius_colour() of the touching ball's radius there: the atoms'
    // (quantised) colour values interpolated linearly over the tangent triangle.
    const Eigen::Vector3d& t0 = tangent[side][0];
    const Eigen::Vector3d nk = (tangent[side][1] - t0).cross(tangent[side][2] - t0);
    double t_lo = 1, t_hi = 0;
    for (int x = 0; x < 3; ++x) {
      const Eigen::Vector3d& p = m.vertices[t[x]];
      const double l1 = (p - t0).cross(tangent[side][2] - t0).dot(nk) / nk.squaredNorm();
      const double l2 = (tangent[side][1] - t0).cross(p - t0).dot(nk) / nk.squaredNorm();
      const double value = (1 - l1 - l2) * level_value(0.5, lo, hi) +
                           l1 * level_value(0.35, lo, hi) + l2 * level_value(0.25, lo, hi);
      EXPECT_LT((m.colours[f][x] - mg::render::radius_colour(value)).norm(), 1e-5)
          << "triangle " << f << " corner " << x;
      t_lo = std::min(t_lo, value);
      t_hi = std::max(t_hi, value);
      EXPECT_TRUE(box.contains(p));
    }
    // No piece straddles a hue break, where the colour map bends.
    for (double tb : {0.25, 0.5, 0.75}) EXPECT_FALSE(t_lo < tb - 1e-9 && tb + 1e-9 < t_hi);
  }
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d& t0 = tangent[k][0];
    EXPECT_NEAR(area[k], (tangent[k][1] - t0).cross(tangent[k][2] - t0).norm() / 2, 1e-12);
  }
}

TEST(PovrayScene, AtomsPrimitivesIgnoreEdgesAndFaces) {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(0, 0, 0), 0.5},
             {Eigen::Vector3d(2, 0, 0), 0.35},
             {Eigen::Vector3d(0.8, 1.6, 0.3), 0.25}};
  const SceneObject atoms{"m", s};
  s.edges = {{0, 1}};
  s.faces = {{0, 1, 2}};
  const SceneObject mesh{"m", s};
  const auto view = mg::render::frame_object(atoms, 160, 120);
  mg::render::SceneOptions rt;
  rt.primitives = mg::garbing::PrimitiveSet::atoms;
  const std::string balls = mg::render::povray_scene({mesh}, view, rt);
  EXPECT_EQ(count(balls, "\nsphere { "), 3u);
  EXPECT_EQ(balls.find("cone {"), std::string::npos);
  EXPECT_EQ(balls.find("mesh2"), std::string::npos);
  // The very text of the atoms alone, which "auto" draws for a file without edges and faces.
  EXPECT_EQ(balls, mg::render::povray_scene({atoms}, view));
  EXPECT_EQ(balls, mg::render::povray_scene({atoms}, view, rt));
  // "auto" draws the envelope of a medial mesh, as "ma" does.
  mg::render::SceneOptions ma;
  ma.primitives = mg::garbing::PrimitiveSet::envelope;
  const std::string envelope = mg::render::povray_scene({mesh}, view);
  EXPECT_EQ(envelope, mg::render::povray_scene({mesh}, view, ma));
  EXPECT_EQ(count(envelope, "\ncone { "), 3u);
  EXPECT_EQ(count(envelope, "mesh2 {"), 1u);
}

TEST(PovrayScene, EdgeWhoseBallHoldsTheOtherHasNoCone) {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(0, 0, 0), 1.0}, {Eigen::Vector3d(0.3, 0, 0), 0.5}};
  s.edges = {{0, 1}, {1, 0}};
  const SceneObject nested{"nested", s};
  const std::string scene =
      mg::render::povray_scene({nested}, mg::render::frame_object(nested, 160, 120));
  EXPECT_EQ(count(scene, "\nsphere { "), 2u);
  EXPECT_TRUE(cones_in(scene).empty());
  EXPECT_NE(scene.find("// cones: 0,"), std::string::npos);
}

TEST(PovrayScene, SlabWithoutTangentTrianglesAddsNoTriangle) {
  // The radius climbs faster than the centres spread (|grad r| > 1): no plane touches all
  // three balls, and the face's hull is its edges' (three cones).
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(0, 0, 0), 1.0},
             {Eigen::Vector3d(1, 0, 0), 1.9},
             {Eigen::Vector3d(0, 1, 0), 1.9}};
  s.faces = {{0, 1, 2}};
  const SceneObject steep{"steep", s};
  const std::string scene =
      mg::render::povray_scene({steep}, mg::render::frame_object(steep, 160, 120));
  EXPECT_EQ(cones_in(scene).size(), 3u);
  EXPECT_EQ(scene.find("mesh2"), std::string::npos);
  EXPECT_NE(scene.find("// slabs: 0 with tangent triangles (1 without)"), std::string::npos);
}

TEST(PovrayScene, SameViewSameCameraWhateverTheObjects) {
  const SceneObject sphere = sphere_object();
  const auto view = mg::render::frame_view(mg::render::bounding_box(sphere), 160, 120);
  const std::string a = mg::render::povray_scene({sphere}, view);
  const std::string b = mg::render::povray_scene({two_atoms()}, view);
  const std::string c = mg::render::povray_scene({sphere, two_atoms()}, view);
  const std::string camera = mg::render::povray_camera(view);
  EXPECT_EQ(block(a, "camera {"), camera);
  EXPECT_EQ(block(b, "camera {"), camera);
  EXPECT_EQ(block(c, "camera {"), camera);
  EXPECT_EQ(count(c, "mesh2 {"), 1u);
  EXPECT_EQ(count(c, "\nsphere { "), 2u);
  // A camera framed on another object differs.
  const auto other = mg::render::frame_view(mg::render::bounding_box(two_atoms()), 160, 120);
  EXPECT_NE(mg::render::povray_camera(other), camera);
}

TEST(FrameObject, MeshVerticesFillTheImageUpToTheMargin) {
  const SceneObject sphere = sphere_object();
  const mg::render::View view = mg::render::frame_object(sphere, 160, 120);
  double fill = 0;
  for (const auto& p : std::get<mg::PolygonSoup>(sphere.geometry).points) {
    const Eigen::Vector3d q = mg::render::project(view, p);
    fill = std::max({fill, std::abs(q.x() - 80) / 80, std::abs(q.y() - 60) / 60});
  }
  EXPECT_NEAR(fill, 1 - mg::render::FramingOptions().margin, 1e-9);
  SceneObject one_point{"dot", mg::PolygonSoup{{{1, 1, 1}}, {}}};
  try {
    mg::render::frame_object(one_point, 160, 120);
    ADD_FAILURE() << "a point was framed";
  } catch (const mg::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("dot: frame_view: the object has zero size"),
              std::string::npos);
  }
}

TEST(PovrayScene, BoundingBoxOfAtomsHoldsTheBalls) {
  const Eigen::AlignedBox3d box = mg::render::bounding_box(two_atoms());
  EXPECT_EQ(box.min(), Eigen::Vector3d(-1.25, -0.75, -0.75));
  EXPECT_EQ(box.max(), Eigen::Vector3d(1.75, 0.75, 0.75));
}

TEST(PovrayScene, BadObjectsAreNamed) {
  const auto view = mg::render::frame_view(mg::render::bounding_box(sphere_object()), 160, 120);
  SceneObject atoms = two_atoms();
  std::get<mg::MedialSurface>(atoms.geometry).atoms[1].radius = -1;
  try {
    mg::render::povray_scene({sphere_object(), atoms}, view);
    ADD_FAILURE() << "negative radius accepted";
  } catch (const mg::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("atoms: atom 1"), std::string::npos) << e.what();
  }
  SceneObject flat{"flat", mg::PolygonSoup{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}}};
  EXPECT_THROW(mg::render::povray_scene({flat}, view), mg::InvalidInput);
  EXPECT_THROW(mg::render::povray_scene({}, view), mg::InvalidInput);
  mg::render::SceneOptions opt;
  opt.mesh_transmit = 1.0;
  EXPECT_THROW(mg::render::povray_scene({sphere_object()}, view, opt), mg::InvalidInput);
}

TEST(ReadSceneObject, ByExtension) {
  mg_test::TempDir dir("render_read");
  const std::string ma = dir.write("s.MA", "2 0 0\nv 0 0 0 1\nv 1 0 0 0.5\n");
  const SceneObject s = mg::render::read_scene_object(ma);
  ASSERT_TRUE(std::holds_alternative<mg::MedialSurface>(s.geometry));
  EXPECT_EQ(std::get<mg::MedialSurface>(s.geometry).atoms.size(), 2u);
  const std::string xyzr = dir.write("s.xyzr", "0 0 0 1\n");
  EXPECT_TRUE(
      std::holds_alternative<mg::MedialSurface>(mg::render::read_scene_object(xyzr).geometry));
  const std::string off = dir.write("t.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(std::holds_alternative<mg::PolygonSoup>(mg::render::read_scene_object(off).geometry));

  EXPECT_THROW(mg::render::read_scene_object(dir.write("x.txt", "0 0 0 1\n")), mg::InvalidInput);
  EXPECT_THROW(mg::render::read_scene_object(dir.file("missing.ma")), mg::IoError);
  EXPECT_THROW(mg::render::read_scene_object(dir.file("missing.off")), mg::IoError);
}

}  // namespace
