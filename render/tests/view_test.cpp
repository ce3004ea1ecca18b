#include "render/view.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "test_util.h"

namespace {

using mg::render::frame_view;
using mg::render::FramingOptions;
using mg::render::View;

/// Largest distance of a box corner from the image centre, as a fraction of the half size.
double fill_fraction(const View& view, const Eigen::AlignedBox3d& box) {
  double fill = 0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p =
        mg::render::project(view, box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
    EXPECT_GT(p.z(), 0) << "corner " << i << " behind the camera";
    fill = std::max({fill, std::abs(p.x() - view.width / 2.0) / (view.width / 2.0),
                     std::abs(p.y() - view.height / 2.0) / (view.height / 2.0)});
  }
  return fill;
}

TEST(FrameView, BoxFillsTheImageUpToTheMargin) {
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-1, 2, 0.5), Eigen::Vector3d(3, 2.5, 1.5));
  for (const auto& [w, h] : {std::pair{800, 600}, std::pair{160, 120}, std::pair{300, 900}}) {
    FramingOptions opt;
    const View view = frame_view(box, w, h, opt);
    EXPECT_NEAR(fill_fraction(view, box), 1.0 - opt.margin, 1e-9) << w << "x" << h;
    EXPECT_LT((view.look_at - box.center()).norm(), 1e-12);
    // The eye lies on the documented direction from the centre.
    EXPECT_GT((view.location - view.look_at).normalized().dot(opt.direction.normalized()),
              1 - 1e-12);
    EXPECT_EQ(view.width, w);
    EXPECT_EQ(view.height, h);
  }
}

TEST(FrameView, OneBallTouchesTheMargin) {
  // A ball seen from distance d spans the half angle asin(r / d); with a 4:3 image the vertical
  // field of view is the tighter one.
  FramingOptions opt;
  const double r = 0.7;
  const View view = frame_view({Eigen::Vector3d(1, 2, 3)}, {r}, 800, 600, opt);
  const double d = (view.location - view.look_at).norm();
  const double tan_v = std::tan(opt.angle * M_PI / 360) * 0.75 * (1 - opt.margin);
  EXPECT_NEAR(std::tan(std::asin(r / d)), tan_v, 1e-12);
  EXPECT_LT((view.look_at - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
  EXPECT_THROW(frame_view({Eigen::Vector3d(0, 0, 0)}, {-1.0}, 8, 6), mg::InvalidInput);
  EXPECT_THROW(frame_view({Eigen::Vector3d(0, 0, 0)}, {1.0, 2.0}, 8, 6), mg::InvalidInput);
  EXPECT_THROW(frame_view({}, {}, 8, 6), mg::InvalidInput);
}

TEST(FrameView, ImageAxesAreRightHanded) {
  // Looking down -z with +y up, +x appears to the right and +y at the top.
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  FramingOptions opt;
  opt.direction = Eigen::Vector3d(0, 0, 1);
  const View view = frame_view(box, 200, 100, opt);
  const Eigen::Vector3d right = mg::render::project(view, Eigen::Vector3d(1, 0, 0));
  const Eigen::Vector3d top = mg::render::project(view, Eigen::Vector3d(0, 1, 0));
  EXPECT_GT(right.x(), 100);
  EXPECT_NEAR(right.y(), 50, 1e-9);
  EXPECT_LT(top.y(), 50);
  EXPECT_NEAR(top.x(), 100, 1e-9);
}

TEST(FrameView, Preconditions) {
  const Eigen::AlignedBox3d box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  EXPECT_THROW(frame_view(Eigen::AlignedBox3d(), 10, 10), mg::InvalidInput);
  EXPECT_THROW(
      frame_view(Eigen::AlignedBox3d(Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones()), 10, 10),
      mg::InvalidInput);
  EXPECT_THROW(frame_view(box, 0, 10), mg::InvalidInput);
  FramingOptions opt;
  opt.direction = Eigen::Vector3d(0, 2, 0);  // parallel to sky
  EXPECT_THROW(frame_view(box, 10, 10, opt), mg::InvalidInput);
  opt = FramingOptions();
  opt.angle = 180;
  EXPECT_THROW(frame_view(box, 10, 10, opt), mg::InvalidInput);
  opt = FramingOptions();
  opt.margin = 0.5;
  EXPECT_THROW(frame_view(box, 10, 10, opt), mg::InvalidInput);
}

TEST(ViewFile, RoundTripIsExact) {
  mg_test::TempDir dir("render_view");
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-1.0 / 3, 0.1, 1e-7),
                                Eigen::Vector3d(2.0 / 7, 0.7, 1.3));
  const View view = frame_view(box, 640, 480);
  mg::render::write_view(view, dir.file("v.json"));
  const View back = mg::render::read_view(dir.file("v.json"));
  EXPECT_EQ(back.location, view.location);
  EXPECT_EQ(back.look_at, view.look_at);
  EXPECT_EQ(back.sky, view.sky);
  EXPECT_EQ(back.angle, view.angle);
  EXPECT_EQ(back.width, 640);
  EXPECT_EQ(back.height, 480);
}

TEST(ViewFile, BadFilesAreRefusedByName) {
  mg_test::TempDir dir("render_view_bad");
  EXPECT_THROW(mg::render::read_view(dir.file("none.json")), mg::IoError);
  const std::string ok = R"("look_at": [0, 0, 0], "sky": [0, 1, 0], "width": 8, "height": 6)";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"not json", "not a JSON view file"},
      {"[1, 2]", "one JSON object"},
      {R"({"location": [0, 0, 5], )" + ok + "}", "\"angle\" must be a number"},
      {R"({"location": [0, 0], "angle": 30, )" + ok + "}", "array of 3 numbers"},
      {R"({"location": [0, 0, 0], "angle": 30, )" + ok + "}", "location and look_at coincide"},
      {R"({"location": [0, 5, 0], "angle": 30, )" + ok + "}", "sky is parallel"},
      {R"({"location": [0, 0, 5], "angle": 0, )" + ok + "}", "angle must be in (0, 180)"},
      // Nothing may follow the object; an integer above 2^63 is not read as a wrapped -1.
      {R"({"location": [0, 0, 5], "angle": 30, )" + ok + "} {}", "not a JSON view file"},
      {R"({"location": [0, 0, 5], "angle": 30, "look_at": [0, 0, 0], "sky": [0, 1, 0], )"
       R"("width": 18446744073709551615, "height": 6})",
       "\"width\" must be in [1, 16384], got 18446744073709551615"},
  };
  for (const auto& [text, message] : cases) {
    const std::string path = dir.write("v.json", text);
    try {
      mg::render::read_view(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const mg::InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

}  // namespace
