#include "core/mesh_io.h"
#include "core/errors.h"
#include "core/mesh_topology.h"
#include "core/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "test_util.h"

namespace {

std::string read_error(const std::string& path) {
  try {
    mg::read_mesh(path);
  } catch (const mg::Error& e) {
    return e.what();
  }
  return "";
}

/// A small closed mesh with awkward coordinates and a quad (polygons must survive OFF/OBJ/PLY).
mg::Mesh awkward_box() {
  mg::PolygonSoup soup = mg::make_box(Eigen::Vector3d(-1.0 / 3.0, 0.1, 1e-7),
                                      Eigen::Vector3d(2.0 / 7.0, 0.7, 12345.678901234567));
  return mg::mesh_from_soup(soup, "box");
}

class MeshRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshRoundTrip, KeepsDoublesAndFaces) {
  mg_test::TempDir dir("mesh_io");
  const std::string ext = GetParam();
  const mg::Mesh mesh = awkward_box();
  const std::string path = dir.file("box" + ext);
  mg::write_mesh(mesh, path);
  const mg::PolygonSoup in = mg::read_polygon_soup(path);
  const mg::PolygonSoup out = mg::soup_from_mesh(mesh);
  ASSERT_EQ(in.points.size(), out.points.size());
  for (std::size_t i = 0; i < in.points.size(); ++i) {
    // STL has no vertex list: points come back merged, in order of first use.
    const Eigen::Vector3d& original =
        ext == ".stl"
            ? *std::min_element(out.points.begin(), out.points.end(),
                                [&](const auto& a, const auto& b) {
                                  return (a - in.points[i]).norm() < (b - in.points[i]).norm();
                                })
            : out.points[i];
    EXPECT_LE((in.points[i] - original).norm(), 1e-12 * original.norm()) << ext;
  }
  const mg::MeshTopology t = mg::mesh_topology(in);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.oriented);
  EXPECT_EQ(t.genus, 0);
  if (ext == ".stl") {
    EXPECT_EQ(in.faces.size(), 12u);  // STL holds triangles: 6 quads -> 12 triangles
  } else {
    EXPECT_EQ(in.faces, out.faces) << ext;
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshRoundTrip, ::testing::Values(".off", ".obj", ".ply", ".stl"),
                         [](const auto& p) { return p.param.substr(1); });

TEST(MeshIo, ExtensionIsCaseInsensitive) {
  mg_test::TempDir dir("mesh_io");
  mg::write_mesh(awkward_box(), dir.file("BOX.OFF"));
  EXPECT_EQ(mg::read_mesh(dir.file("BOX.OFF")).n_faces(), 6u);
}

TEST(MeshIo, OffVariantsParse) {
  mg_test::TempDir dir("mesh_io");
  // Counts on the header line, comments, colours after faces.
  const auto path = dir.write("t.off",
                              "OFF 4 4 6 # tetrahedron\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                              "3 0 2 1 255 0 0\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const mg::Mesh m = mg::read_mesh(path);
  EXPECT_EQ(m.n_vertices(), 4u);
  EXPECT_EQ(m.n_faces(), 4u);
}

TEST(MeshIo, RefusesBadFilesWithNameLineAndReason) {
  mg_test::TempDir dir("mesh_io");
  const std::string tet = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  EXPECT_EQ(read_error(dir.file("missing.off")),
            dir.file("missing.off") + ": cannot open for reading");
  EXPECT_EQ(read_error(dir.write("a.xyz", "")),
            dir.file("a.xyz") + ": unknown mesh extension (expected .off, .obj, .ply or .stl)");
  EXPECT_EQ(read_error(dir.write("e.off", "")), dir.file("e.off") + ": empty file");
  EXPECT_EQ(read_error(dir.write("h.off", "PLY\n")),
            dir.file("h.off") + ":1: expected an OFF header, got 'PLY'");
  EXPECT_EQ(read_error(dir.write("c.off", "OFF\n4 4 6\n" + tet + "3 0 2 1\n")),
            dir.file("c.off") + ": file ends early: expected 4 faces, found 1");
  EXPECT_EQ(read_error(dir.write("n.off", "OFF\n1 0 0\n0 nan 0\n")),
            dir.file("n.off") + ":3: vertex 0 has a non-finite coordinate");
  EXPECT_EQ(read_error(dir.write("x.off", "OFF\n1 0 0\n0 a 0\n")),
            dir.file("x.off") + ":3: not a number: 'a'");
  EXPECT_EQ(read_error(dir.write("r.off", "OFF\n4 1 0\n" + tet + "3 0 1 4\n")),
            dir.file("r.off") + ":7: face 0: vertex index 4 out of range [0, 4)");
  EXPECT_EQ(read_error(dir.write("d.off", "OFF\n4 1 0\n" + tet + "3 0 1 1\n")),
            dir.file("d.off") + ":7: face 0 repeats vertex 1");
  EXPECT_EQ(read_error(dir.write("s.off", "OFF\n4 1 0\n" + tet + "2 0 1\n")),
            dir.file("s.off") + ":7: face 0 has 2 vertices (3 or more needed)");
  EXPECT_EQ(read_error(dir.write("z.off", "OFF\n4 0 0\n" + tet)), dir.file("z.off") + ": no faces");
  EXPECT_NE(read_error(dir.write("bad.obj", "v 0 0 0\nf 1 2 3\n")), "");
  // Found by the fuzz targets (core/fuzz/seeds/*/found_*): a huge count reserved memory
  // before the file could fail; CGAL's PLY reader read a property before any element out of
  // an empty vector.
  EXPECT_EQ(read_error(dir.write("huge.off", "OFF\n999999999 1 0\n0 0 0\n")),
            dir.file("huge.off") + ": file ends early: expected 999999999 vertices, found 1");
  EXPECT_EQ(read_error(dir.write("int.off", "OFF\n99999999999 1 0\n0 0 0\n")),
            dir.file("int.off") + ":2: vertex count 99999999999 exceeds 2147483647");
  EXPECT_EQ(read_error(dir.write("p.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n")),
            dir.file("p.ply") + ":3: a property before any element");
  EXPECT_EQ(read_error(dir.write("k.ply", "ply\nformat ascii 1.0\ndlement vertex 1\nend_header\n")),
            dir.file("k.ply") + ":3: unknown PLY header keyword 'dlement'");
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\n";
  EXPECT_EQ(read_error(dir.write("i.ply", header + "property float x\nproperty int32 y\n"
                                                   "property float z\nend_header\n")),
            dir.file("i.ply") + ":5: coordinate 'y' must be float or double, got 'int32'");
  EXPECT_EQ(read_error(dir.write("v.ply", header + "property float x\nproperty float y\n"
                                                   "property float z\nelement face 1\n"
                                                   "property int vertex_indices\nend_header\n")),
            dir.file("v.ply") + ":8: 'vertex_indices' must be a list of integers");
  EXPECT_EQ(
      read_error(dir.write("l.ply", header + "property float x\nproperty float y\n"
                                             "property float z\nelement face 1\n"
                                             "property list int int vertex_indices\nend_header\n"
                                             "0 0 0\n1 0 0\n0 1 0\n-5 0 1 2\n")),
      dir.file("l.ply") + ": element 'face' row 0: list count -5 is negative");
}

/// A binary PLY: a header, then the body's bytes as written.
std::string binary_ply(const std::string& format, const std::string& elements,
                       const std::vector<unsigned char>& body) {
  return "ply\nformat " + format + " 1.0\n" + elements + "end_header\n" +
         std::string(body.begin(), body.end());
}

/// The bytes of a float and of an int32, little or big endian.
void put(std::vector<unsigned char>& out, std::uint32_t bits, bool little) {
  for (int i = 0; i < 4; ++i) out.push_back((bits >> (little ? 8 * i : 24 - 8 * i)) & 0xff);
}
void put_float(std::vector<unsigned char>& out, float f, bool little) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, 4);
  put(out, bits, little);
}

/// The tetrahedron of core/fuzz/seeds/ply/tetra.ply, binary, faces as `list uchar int`.
std::string binary_tetra(bool little) {
  std::vector<unsigned char> body;
  for (const auto& p : {std::array<float, 3>{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}})
    for (float c : p) put_float(body, c, little);
  for (const auto& f : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
    body.push_back(3);
    for (int v : f) put(body, static_cast<std::uint32_t>(v), little);
  }
  return binary_ply(little ? "binary_little_endian" : "binary_big_endian",
                    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 4\nproperty list uchar int vertex_indices\n",
                    body);
}

TEST(MeshIo, BinaryPlyIsRead) {
  mg_test::TempDir dir("mesh_io");
  for (bool little : {true, false}) {
    const mg::Mesh m = mg::read_mesh(dir.write("b.ply", binary_tetra(little)));
    EXPECT_EQ(m.n_vertices(), 4u);
    EXPECT_EQ(m.n_faces(), 4u);
    EXPECT_TRUE(mg::mesh_topology(mg::soup_from_mesh(m)).closed);
  }
}

// Issue 21: CGAL's PLY reader sizes its buffers by the file's counts: a 200-byte file made it
// allocate up to 16 GB (out of memory under fuzz_ply). Counts are now checked against the
// bytes left before CGAL reads them (core/fuzz/seeds/ply/found_*_count*.ply).
TEST(MeshIo, Issue21PlyCountsMustFitInTheFile) {
  mg_test::TempDir dir("mesh_io");
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list int int vertex_indices\n";
  const std::string ascii = "ply\nformat ascii 1.0\n";
  // A row count no body can hold (ASCII: 2 bytes a value at least; binary: the row's size).
  EXPECT_EQ(read_error(dir.write(
                "r.ply", ascii + "element vertex 2147483648\n" + xyz + "end_header\n0 0 0\n")),
            dir.file("r.ply") +
                ":3: element 'vertex' announces 2147483648 rows, but the 6 bytes left hold at "
                "most 1");
  EXPECT_EQ(read_error(dir.write(
                "rb.ply", binary_ply("binary_little_endian", "element vertex 2147483648\n" + xyz,
                                     std::vector<unsigned char>(24, 0)))),
            dir.file("rb.ply") +
                ":3: element 'vertex' announces 2147483648 rows, but the 24 bytes left hold at "
                "most 2");
  // A list count of 2^31 - 1: out of a uchar's range, past the end of the file, more items
  // than bytes left.
  const std::string tet = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(read_error(dir.write("u.ply", ascii + "element vertex 3\n" + xyz +
                                              "element face 1\n"
                                              "property list uchar int vertex_indices\n"
                                              "end_header\n" +
                                              tet + "2147483647 0 1 2\n")),
            dir.file("u.ply") + ": element 'face' row 0: '2147483647' is not a uchar");
  EXPECT_EQ(read_error(dir.write("a.ply", ascii + "element vertex 3\n" + xyz + faces +
                                              "end_header\n" + tet + "2147483647 0 1 2\n")),
            dir.file("a.ply") + ": the file ends in row 0 of element 'face' (1 announced)");
  std::vector<unsigned char> body(36, 0);
  put(body, 0x7fffffff, true);
  for (int v : {0, 1, 2}) put(body, static_cast<std::uint32_t>(v), true);
  EXPECT_EQ(
      read_error(dir.write(
          "b.ply", binary_ply("binary_little_endian", "element vertex 3\n" + xyz + faces, body))),
      dir.file("b.ply") +
          ": element 'face' row 0: list count 2147483647 needs 8589934588 bytes, 12 are left");
  // A negative list count (the seed found_negative_list_count.ply), and a malformed count.
  body.assign(36, 0);
  body.push_back(0xff);
  EXPECT_EQ(read_error(dir.write("n.ply", binary_ply("binary_big_endian",
                                                     "element vertex 3\n" + xyz +
                                                         "element face 1\n"
                                                         "property list char int vertex_indices\n",
                                                     body))),
            dir.file("n.ply") + ": element 'face' row 0: list count -1 is negative");
  EXPECT_EQ(read_error(dir.write("c.ply", ascii + "element vertex -1\n" + xyz + "end_header\n")),
            dir.file("c.ply") +
                ":3: expected 'element NAME COUNT', the count an integer from 0 to 2^64 - 1");
  EXPECT_EQ(read_error(dir.write("t.ply", ascii + "element vertex 3\nproperty int64 x\n")),
            dir.file("t.ply") + ":4: coordinate 'x' must be float or double, got 'int64'");
  EXPECT_EQ(read_error(dir.write("q.ply", ascii + "element vertex 3\n" + xyz +
                                              "property int64 quality\nend_header\n")),
            dir.file("q.ply") + ":7: unknown PLY property type 'int64'");
  EXPECT_EQ(read_error(dir.write("e.ply", ascii + "element vertex 3\nend_header\n")),
            dir.file("e.ply") + ":3: element 'vertex' announces 3 rows but has no properties");
  EXPECT_EQ(read_error(dir.write("f.ply", "ply\nformat binary_middle_endian 1.0\n")),
            dir.file("f.ply") + ":2: unknown PLY format 'binary_middle_endian'");
}

TEST(MeshIo, NonManifoldInputIsRefusedNamingTheElement) {
  mg_test::TempDir dir("mesh_io");
  // Three triangles on one edge (0, 1).
  const auto fin = dir.write(
      "fin.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  EXPECT_EQ(read_error(fin), fin + ": edge (0, 1) is shared by 3 faces");
  // Two triangles touching at vertex 0 only (a bow tie).
  const auto bowtie =
      dir.write("bow.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n");
  EXPECT_EQ(read_error(bowtie),
            bowtie + ": vertex 0 is non-manifold (its faces form separate fans)");
  // Inconsistent orientation.
  const auto flip =
      dir.write("flip.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n");
  EXPECT_EQ(
      read_error(flip),
      flip +
          ": faces 0 and 1 run along edge (1, 2) in the same direction (inconsistent orientation)");
}

TEST(MeshIo, WritingToAMissingFolderFailsWithoutAFile) {
  EXPECT_THROW(mg::write_mesh(awkward_box(), "/nonexistent/dir/box.off"), mg::IoError);
  EXPECT_THROW(mg::write_mesh(awkward_box(), "/tmp/box.unknown"), mg::InvalidInput);
}

}  // namespace
