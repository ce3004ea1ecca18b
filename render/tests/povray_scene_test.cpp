#include "render/povray_scene.h"

#include "core/errors.h"
#include "core/shapes.h"

#include <gtest/gtest.h>

#include <regex>

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
