#include "core/medial_surface.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

mg::MedialSurface parse(const std::string& text) {
  std::istringstream in(text);
  return mg::parse_medial_surface(in, "test.ma");
}

/// The message of the InvalidInput that parsing `text` throws ("" if none).
std::string parse_error(const std::string& text) {
  try {
    parse(text);
  } catch (const mg::InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(MedialSurface, ParsesMaWithCommentsBlankLinesAndConnectivity) {
  const auto s = parse(
      "# a comment\n"
      "3 2 1   # header\n"
      "\n"
      "v 0 0 0 1\n"
      "v 1.5 0 0 0.5\n"
      "e 0 1\n"
      "v 0 2 0 0.25\n"
      "e 1 2\n"
      "f 0 1 2\n");
  ASSERT_EQ(s.atoms.size(), 3u);
  EXPECT_EQ(s.atoms[1].centre, Eigen::Vector3d(1.5, 0, 0));
  EXPECT_EQ(s.atoms[2].radius, 0.25);
  ASSERT_EQ(s.edges.size(), 2u);
  EXPECT_EQ(s.edges[1][0], 1);
  EXPECT_EQ(s.edges[1][1], 2);
  ASSERT_EQ(s.faces.size(), 1u);
  EXPECT_EQ(s.faces[0][2], 2);
}

TEST(MedialSurface, ParsesPlainXyzr) {
  const auto s = parse("0 0 0 1\n# c\n1 2 3 0.5\n");
  ASSERT_EQ(s.atoms.size(), 2u);
  EXPECT_EQ(s.atoms[1].centre, Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(s.edges.empty());
}

TEST(MedialSurface, RoundTripIsExact) {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(0.1, 1.0 / 3.0, -2e-17), std::sqrt(2.0)},
             {Eigen::Vector3d(1e10, -7.25, 3.14159265358979), 1e-12},
             {Eigen::Vector3d(0, 0, 1), 0.3}};
  s.edges = {{0, 1}, {1, 2}};
  s.faces = {{0, 1, 2}};
  const auto path = std::filesystem::temp_directory_path() / "mg_round_trip.ma";
  mg::write_medial_surface(s, path.string());
  const auto t = mg::read_medial_surface(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(t.atoms.size(), s.atoms.size());
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    EXPECT_EQ(t.atoms[i].centre, s.atoms[i].centre);  // bit-exact with 17 digits
    EXPECT_EQ(t.atoms[i].radius, s.atoms[i].radius);
  }
  EXPECT_EQ(t.edges, s.edges);
  EXPECT_EQ(t.faces, s.faces);
}

TEST(MedialSurface, RefusesBadInputWithFileLineAndReason) {
  const std::pair<const char*, const char*> cases[] = {
      {"", "test.ma: empty file, no atoms"},
      {"# only a comment\n\n", "test.ma: empty file, no atoms"},
      {"0 0 0\n", "test.ma: no atoms"},
      {"2 0 0\nv 0 0 0 1\n", "test.ma: header announces 2 atoms ('v' lines), found 1"},
      {"1 0 0\nv 0 0 0 1\nv 1 0 0 1\n", "test.ma:3: more 'v' lines than the header's nv = 1"},
      {"1 0 0\nv 0 zero 0 1\n", "test.ma:2: y is not a number: 'zero'"},
      {"1 0 0\nv 0 0 0 nan\n", "test.ma:2: radius must be finite, got nan"},
      {"1 0 0\nv 0 0 0 inf\n", "test.ma:2: radius must be finite, got inf"},
      {"1 0 0\nv inf 0 0 1\n", "test.ma:2: centre must be finite"},
      {"1 0 0\n\nv 0 0 0 -0.3\n", "test.ma:3: radius must be >= 0, got -0.3"},
      {"1 0 0\nv 0 0 0 -1e-300\n", "test.ma:2: radius must be >= 0, got -1e-300"},
      {"2 1 0\nv 0 0 0 1\nv 1 0 0 1\ne 0 2\n", "test.ma:4: edge index 2 out of range [0, 2)"},
      {"3 0 1\nv 0 0 0 1\nv 1 0 0 1\nv 2 0 0 1\nf 0 1 -1\n",
       "test.ma:5: face index -1 out of range [0, 3)"},
      {"1 0 0\nv 0 0 0\n", "test.ma:2: expected 'v x y z r', got 4 fields"},
      {"1 0 0\nx 0 0 0 1\n", "test.ma:2: unknown record 'x' (expected v, e or f)"},
      {"0 0 0 1\n1 1 1\n",
       "test.ma:2: expected a header 'nv ne nf' or an atom 'x y z r', got 3 fields"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(parse_error(text), message) << text;
}

TEST(MedialSurface, ReadingAMissingFileIsAnIoError) {
  EXPECT_THROW(mg::read_medial_surface("/nonexistent/dir/none.ma"), mg::IoError);
}

TEST(MedialSurface, ValidateNamesTheFirstBadAtom) {
  mg::MedialSurface s;
  EXPECT_THROW(mg::validate(s), mg::InvalidInput);
  s.atoms = {{Eigen::Vector3d::Zero(), 1.0}, {Eigen::Vector3d::Zero(), -1.0}};
  try {
    mg::validate(s);
    FAIL() << "negative radius accepted";
  } catch (const mg::InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), "atom 1: radius must be >= 0, got -1");
  }
  s.atoms[1].radius = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mg::validate(s), mg::InvalidInput);
  s.atoms[1].radius = 1;
  s.edges = {{0, 5}};
  EXPECT_THROW(mg::validate(s), mg::InvalidInput);
}

TEST(MedialSurface, ParsesMatfpFlagsOnVerticesEdgesAndFaces) {
  // MATFP: `v x y z r TYPE FLAG`; feature flags on edges and faces; extra integer fields too.
  const auto s = parse(
      "4 3 2\n"
      "v 0 0 0 1 0 1\n"
      "v 1.5 0 0 0.5 1 0\n"
      "v 0 2 0 1e-12 2 -1\n"
      "v 0 0 3 0.25 0 +7 123456789012345678901234567890\n"
      "e 0 1 1\n"
      "e 1 2 0\n"
      "e 2 3\n"
      "f 0 1 2 1\n"
      "f 1 2 3 0 4\n");
  ASSERT_EQ(s.atoms.size(), 4u);
  EXPECT_EQ(s.atoms[1].centre, Eigen::Vector3d(1.5, 0, 0));
  EXPECT_EQ(s.atoms[1].radius, 0.5);
  EXPECT_EQ(s.atoms[2].radius, 1e-12);
  EXPECT_EQ(s.atoms[3].centre, Eigen::Vector3d(0, 0, 3));
  EXPECT_EQ(s.atoms[3].radius, 0.25);
  const std::vector<std::array<int, 2>> edges = {{0, 1}, {1, 2}, {2, 3}};
  const std::vector<std::array<int, 3>> faces = {{0, 1, 2}, {1, 2, 3}};
  EXPECT_EQ(s.edges, edges);
  EXPECT_EQ(s.faces, faces);
  // The flags are dropped: writing gives the plain `.ma` records.
  std::ostringstream out;
  mg::format_medial_surface(out, s);
  EXPECT_EQ(out.str().rfind("4 3 2\nv 0 0 0 1\nv 1.5 0 0 0.5\n", 0), 0u) << out.str();
  EXPECT_NE(out.str().find("\ne 0 1\ne 1 2\ne 2 3\nf 0 1 2\nf 1 2 3\n"), std::string::npos)
      << out.str();
}

TEST(MedialSurface, RefusesNonIntegerTrailingFieldsNamingTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"1 0 0\nv 0 0 0 1 0 0.5\n",
       "test.ma:2: field 7 after 'v x y z r' is not an integer flag: '0.5'"},
      {"1 0 0\n# c\nv 0 0 0 1 sharp\n",
       "test.ma:3: field 6 after 'v x y z r' is not an integer flag: 'sharp'"},
      {"2 1 0\nv 0 0 0 1\nv 1 0 0 1\ne 0 1 1e3\n",
       "test.ma:4: field 4 after 'e i j' is not an integer flag: '1e3'"},
      {"3 0 1\nv 0 0 0 1\nv 1 0 0 1\nv 2 0 0 1\nf 0 1 2 -\n",
       "test.ma:5: field 5 after 'f i j k' is not an integer flag: '-'"},
      {"3 0 1\nv 0 0 0 1\nv 1 0 0 1\nv 2 0 0 1\nf 0 1 2 1 x\n",
       "test.ma:5: field 6 after 'f i j k' is not an integer flag: 'x'"},
      // The plain format takes no flags.
      {"0 0 0 1 1\n", "test.ma:1: expected a header 'nv ne nf' or an atom 'x y z r', got 5 fields"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(parse_error(text), message) << text;
}

TEST(MedialSurface, ZeroRadiusIsValidNegativeIsNot) {
  const auto s = parse("2 1 0\nv 0 0 0 0\nv 1 0 0 1e-12\ne 0 1\n");
  ASSERT_EQ(s.atoms.size(), 2u);
  EXPECT_EQ(s.atoms[0].radius, 0.0);
  EXPECT_EQ(s.atoms[1].radius, 1e-12);
  EXPECT_NO_THROW(mg::validate(s));
  EXPECT_EQ(parse("0 0 0 0\n").atoms[0].radius, 0.0);  // plain format too
  EXPECT_EQ(parse_error("1 0 0\nv 0 0 0 -1e-12\n"), "test.ma:2: radius must be >= 0, got -1e-12");

  mg::MedialSurface t;
  t.atoms = {{Eigen::Vector3d::Zero(), 0.0}, {Eigen::Vector3d::Ones(), 1e-12}};
  EXPECT_NO_THROW(mg::validate(t));
  for (double bad :
       {-1e-12, -1.0, std::numeric_limits<double>::quiet_NaN(),
        std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    t.atoms[1].radius = bad;
    EXPECT_THROW(mg::validate(t), mg::InvalidInput) << bad;
  }
}

TEST(MedialSurface, RefusesDegenerateEdgesAndFacesNamingTheLine) {
  const std::string atoms = "v 0 0 0 1\nv 1 0 0 1\nv 2 0 0 1\nv 3 0 0 1\n";
  const std::pair<std::string, std::string> cases[] = {
      {"4 1 0\n" + atoms + "e 3 3\n", "test.ma:6: edge joins atom 3 to itself"},
      {"4 0 1\n" + atoms + "f 1 1 2\n", "test.ma:6: face repeats atom 1"},
      {"4 0 1\n" + atoms + "f 1 2 1\n", "test.ma:6: face repeats atom 1"},
      {"4 0 1\n" + atoms + "f 0 2 2 1\n", "test.ma:6: face repeats atom 2"},
      {"4 1 0\n" + atoms + "e 1 4\n", "test.ma:6: edge index 4 out of range [0, 4)"},
      {"4 1 0\ne 0 0\n" + atoms, "test.ma:2: edge joins atom 0 to itself"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(parse_error(text), message) << text;
}

TEST(MedialSurface, AHugeHeaderCountFailsAtTheCountNotInAnAllocation) {
  // Found by fuzz_ma (core/fuzz/seeds/ma/found_huge_count.ma).
  const std::pair<std::string, std::string> cases[] = {
      {"99999999999999 0 0\nv 0 0 0 1\n",
       "test.ma: header announces 99999999999999 atoms ('v' lines), found 1"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(parse_error(text), message) << text;
}

TEST(MedialSurface, ValidateRefusesDegenerateEdgesAndFacesByIndex) {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d::Zero(), 1.0}, {Eigen::Vector3d::Ones(), 1.0}};
  auto message = [&s]() -> std::string {
    try {
      mg::validate(s);
    } catch (const mg::InvalidInput& e) {
      return e.what();
    }
    return "";
  };
  s.edges = {{0, 1}, {1, 1}};
  EXPECT_EQ(message(), "edge 1: joins atom 1 to itself");
  s.edges = {{0, 1}};
  s.faces = {{0, 1, 0}};
  EXPECT_EQ(message(), "face 0: repeats atom 0");
  s.faces = {{0, 1, 2}};
  EXPECT_EQ(message(), "face 0: index 2 out of range [0, 2)");
}

TEST(MedialSurface, DuplicateEdgesAndFacesAreKeptAsWritten) {
  const std::string text =
      "3 5 2\n"
      "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\n"
      "e 0 1\ne 0 1\ne 1 0\ne 1 2\ne 2 0\n"  // twice, reversed, and sides of the face
      "f 0 1 2\nf 0 1 2\n";
  const auto s = parse(text);
  const std::vector<std::array<int, 2>> edges = {{0, 1}, {0, 1}, {1, 0}, {1, 2}, {2, 0}};
  const std::vector<std::array<int, 3>> faces = {{0, 1, 2}, {0, 1, 2}};
  EXPECT_EQ(s.edges, edges);
  EXPECT_EQ(s.faces, faces);
  EXPECT_NO_THROW(mg::validate(s));
  std::ostringstream out;
  mg::format_medial_surface(out, s);
  EXPECT_EQ(out.str(), text);  // the writer writes what it holds
}

TEST(MedialSurface, RoundTripWithZeroRadiiAndDroppedFlagsIsExact) {
  const auto s = parse(
      "3 2 1\n"
      "v 0.1 0.33333333333333331 -2e-17 0 1 0\n"
      "v 1e10 -7.25 3.14159265358979 1e-12 2 1\n"
      "v 0 0 1 0.3 0 0\n"
      "e 0 1 1\ne 1 2 0\nf 0 1 2 1\n");
  std::ostringstream once;
  mg::format_medial_surface(once, s);
  std::istringstream in(once.str());
  const auto t = mg::parse_medial_surface(in, "again.ma");
  ASSERT_EQ(t.atoms.size(), s.atoms.size());
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    EXPECT_EQ(t.atoms[i].centre, s.atoms[i].centre);
    EXPECT_EQ(t.atoms[i].radius, s.atoms[i].radius);
  }
  EXPECT_EQ(t.atoms[0].radius, 0.0);
  EXPECT_EQ(t.edges, s.edges);
  EXPECT_EQ(t.faces, s.faces);
  std::ostringstream twice;
  mg::format_medial_surface(twice, t);
  EXPECT_EQ(twice.str(), once.str());
}

TEST(MedialSurface, MortonCodeInterleavesTwentyOneBitsPerAxis) {
  EXPECT_EQ(mg::morton_code(1, 0, 0), 1u);
  EXPECT_EQ(mg::morton_code(0, 1, 0), 2u);
  EXPECT_EQ(mg::morton_code(0, 0, 1), 4u);
  EXPECT_EQ(mg::morton_code(3, 0, 0), 9u);  // bits 0 and 3
  EXPECT_EQ(mg::morton_code(0x1FFFFF, 0x1FFFFF, 0x1FFFFF), (std::uint64_t(1) << 63) - 1);
  EXPECT_EQ(mg::morton_code(std::uint64_t(1) << 21, 0, 0), 0u);  // bits above 21 ignored
}

TEST(MedialSurface, SpatiallySortedIsZOrderWithConnectivityRenumbered) {
  // The eight corners of a cube, listed backwards, and a copy of corner (1, 1, 0) with another
  // radius: Z-order puts x in the lowest bit, then y, then z; equal centres go by radius.
  mg::MedialSurface s;
  for (int k = 7; k >= 0; --k)
    s.atoms.push_back({Eigen::Vector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1), 0.1 + 0.01 * k});
  s.atoms.push_back({Eigen::Vector3d(1, 1, 0), 0.05});
  s.edges = {{0, 8}, {7, 1}};
  s.faces = {{8, 0, 3}};
  std::vector<int> old_index;
  const mg::MedialSurface t = mg::spatially_sorted(s, &old_index);
  ASSERT_EQ(t.atoms.size(), 9u);
  ASSERT_EQ(old_index.size(), 9u);
  // Corner k of the cube was atom 7 - k; corner 3 comes after its smaller copy (atom 8).
  const std::vector<int> expected = {7, 6, 5, 8, 4, 3, 2, 1, 0};
  EXPECT_EQ(old_index, expected);
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_EQ(t.atoms[k].centre, s.atoms[old_index[k]].centre);
    EXPECT_EQ(t.atoms[k].radius, s.atoms[old_index[k]].radius);
  }
  // Edges and faces join the same balls as before, in the same order and direction.
  ASSERT_EQ(t.edges.size(), 2u);
  ASSERT_EQ(t.faces.size(), 1u);
  for (std::size_t e = 0; e < 2; ++e)
    for (int end = 0; end < 2; ++end) EXPECT_EQ(old_index[t.edges[e][end]], s.edges[e][end]);
  for (int corner = 0; corner < 3; ++corner)
    EXPECT_EQ(old_index[t.faces[0][corner]], s.faces[0][corner]);
  // Inside the box the axes' bits interleave: (0, 1, 0) comes before (2, 0, 0), which comes
  // before (0, 0, 2); sorting by (z, y, x) or (x, y, z) would order them otherwise.
  mg::MedialSurface w;
  for (const auto& p :
       {Eigen::Vector3d(3, 3, 3), Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(2, 0, 0),
        Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 0)})
    w.atoms.push_back({p, 0.5});
  std::vector<int> w_order;
  mg::spatially_sorted(w, &w_order);
  EXPECT_EQ(w_order, (std::vector<int>{4, 3, 2, 1, 0}));
  // Any order of the same atoms sorts the same.
  mg::MedialSurface u;
  u.atoms.assign(s.atoms.rbegin(), s.atoms.rend());
  const mg::MedialSurface v = mg::spatially_sorted(u);
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_EQ(v.atoms[k].centre, t.atoms[k].centre);
    EXPECT_EQ(v.atoms[k].radius, t.atoms[k].radius);
  }
}

TEST(MedialSurface, FailedWriteLeavesNoFile) {
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d::Zero(), 1.0}};
  EXPECT_THROW(mg::write_medial_surface(s, "/nonexistent/dir/out.ma"), mg::IoError);
  EXPECT_FALSE(std::filesystem::exists("/nonexistent/dir/out.ma"));
}

}  // namespace
