#pragma once
// Small helpers shared by this module's tests.

#include "core/mesh.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace mg_test {

/// A fresh folder under the system temp folder, removed with the object.
class TempDir {
 public:
  explicit TempDir(const std::string& tag)
      : path_(std::filesystem::temp_directory_path() /
              ("mg_" + tag + "_" +
               std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
               std::to_string(reinterpret_cast<std::uintptr_t>(this)))) {
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name)) << text;
    return file(name);
  }

 private:
  std::filesystem::path path_;
};

/// Signed volume enclosed by a closed soup (faces fanned): positive when faces are CCW from
/// outside.
inline double signed_volume(const mg::PolygonSoup& soup) {
  double v = 0;
  for (const auto& t : mg::fan_triangles(soup).corners)
    v += soup.points[t[0]].dot(soup.points[t[1]].cross(soup.points[t[2]])) / 6;
  return v;
}

}  // namespace mg_test
