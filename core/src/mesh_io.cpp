#include "core/mesh_io.h"

#include "ply_check.h"

#include "core/atomic_file.h"
#include "core/errors.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace mg {

// Defined in mesh_io_cgal.cpp (kept apart: it is the one TU here that includes CGAL).
bool read_polygon_soup_with_cgal(const std::string& path, PolygonSoup& soup);

namespace {

const char* const kUnknownExtension = "unknown mesh extension (expected .off, .obj, .ply or .stl)";

/// OFF reader with line numbers. Accepts OFF, COFF, NOFF and CNOFF headers (extra per-vertex
/// and per-face fields are ignored), counts on the header line or the next one, `#` comments.
class OffParser {
  static constexpr long kMaxReserve = 1 << 20;  ///< elements reserved ahead of the file

 public:
  OffParser(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  PolygonSoup parse() {
    if (!next_line()) throw InvalidInput(name_ + ": empty file");
    const std::string magic = tokens_.front();
    static const char* accepted[] = {"OFF", "COFF", "NOFF", "CNOFF", "NCOFF"};
    if (std::find(std::begin(accepted), std::end(accepted), magic) == std::end(accepted))
      fail("expected an OFF header, got '" + magic + "'");
    tokens_.erase(tokens_.begin());
    if (!tokens_.empty() && tokens_.front() == "BINARY") fail("binary OFF is not supported");
    if (tokens_.empty() && !next_line()) fail_eof("the counts 'nv nf ne'");
    if (tokens_.size() < 2) fail("expected the counts 'nv nf ne'");
    const long nv = count(0, "vertex"), nf = count(1, "face");

    PolygonSoup soup;
    // The header's counts are not trusted with memory: a file that claims 10^9 vertices and
    // holds few fails at its end, not in an allocation (found by fuzz_off).
    soup.points.reserve(static_cast<std::size_t>(std::min(nv, kMaxReserve)));
    for (long i = 0; i < nv; ++i) {
      if (!next_line()) fail_eof(std::to_string(nv) + " vertices, found " + std::to_string(i));
      if (tokens_.size() < 3) fail("expected a vertex 'x y z'");
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) p[k] = real(k);
      if (!p.allFinite()) fail("vertex " + std::to_string(i) + " has a non-finite coordinate");
      soup.points.push_back(p);
    }
    soup.faces.reserve(static_cast<std::size_t>(std::min(nf, kMaxReserve)));
    for (long f = 0; f < nf; ++f) {
      if (!next_line()) fail_eof(std::to_string(nf) + " faces, found " + std::to_string(f));
      const long k = integer(0, "face size");
      if (k < 3)
        fail("face " + std::to_string(f) + " has " + std::to_string(k) +
             " vertices (3 or more needed)");
      if (static_cast<long>(tokens_.size()) < k + 1)
        fail("face " + std::to_string(f) + " announces " + std::to_string(k) + " vertices, lists " +
             std::to_string(tokens_.size() - 1));
      std::vector<int> face;
      face.reserve(static_cast<std::size_t>(k));
      for (long j = 1; j <= k; ++j) {
        const long v = integer(static_cast<std::size_t>(j), "vertex index");
        if (v < 0 || v >= nv)
          fail("face " + std::to_string(f) + ": vertex index " + std::to_string(v) +
               " out of range [0, " + std::to_string(nv) + ")");
        if (std::find(face.begin(), face.end(), static_cast<int>(v)) != face.end())
          fail("face " + std::to_string(f) + " repeats vertex " + std::to_string(v));
        face.push_back(static_cast<int>(v));
      }
      soup.faces.push_back(std::move(face));
    }
    return soup;
  }

 private:
  /// The next line with a word, split at white space (as a stream's >> splits) up to a '#'.
  bool next_line() {
    while (std::getline(in_, text_)) {
      ++line_;
      const auto hash = text_.find('#');
      if (hash != std::string::npos) text_.erase(hash);
      std::size_t n = 0;
      for (std::size_t i = 0; i < text_.size();) {
        if (std::isspace(static_cast<unsigned char>(text_[i]))) {
          ++i;
          continue;
        }
        std::size_t j = i;
        while (j < text_.size() && !std::isspace(static_cast<unsigned char>(text_[j]))) ++j;
        if (n == tokens_.size()) tokens_.emplace_back();
        tokens_[n++].assign(text_, i, j - i);
        i = j;
      }
      tokens_.resize(n);
      if (n > 0) return true;
    }
    return false;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidInput(name_ + ":" + std::to_string(line_) + ": " + what);
  }
  [[noreturn]] void fail_eof(const std::string& expected) const {
    throw InvalidInput(name_ + ": file ends early: expected " + expected);
  }

  double real(std::size_t k) const {
    const std::string& t = tokens_[k];
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size()) fail("not a number: '" + t + "'");
    return x;
  }

  long integer(std::size_t k, const char* what) const {
    const std::string& t = tokens_[k];
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(t.c_str(), &end, 10);
    if (end != t.c_str() + t.size() || errno != 0)
      fail(std::string(what) + " is not an integer: '" + t + "'");
    return v;
  }

  long count(std::size_t k, const char* what) const {
    const long n = integer(k, (std::string(what) + " count").c_str());
    if (n < 0) fail(std::string("negative ") + what + " count");
    if (n > std::numeric_limits<int>::max())
      fail(std::string(what) + " count " + std::to_string(n) + " exceeds " +
           std::to_string(std::numeric_limits<int>::max()));
    return n;
  }

  std::istream& in_;
  std::string name_;
  int line_ = 0;
  std::string text_;                 // the current line
  std::vector<std::string> tokens_;  // its words (kept allocated from line to line)
};

// Writers: ASCII, 17 significant digits. (OpenMesh 9.0's writers go through single-precision
// points whatever the traits, which breaks every 1e-9 check downstream: measured 1e-8 relative
// error on a round trip, so the four formats are written here.)
// The coordinates go through std::to_chars with printf's %.17g, which is what the stream's
// precision(17) and default float field produce, at a fraction of the stream's cost.
void write_vertex(std::ostream& out, const Eigen::Vector3d& p) {
  char text[3 * 32];
  char* end = text;
  for (int a = 0; a < 3; ++a) {
    if (a > 0) *end++ = ' ';
    end = std::to_chars(end, text + sizeof(text), p[a], std::chars_format::general, 17).ptr;
  }
  out.write(text, static_cast<std::streamsize>(end - text));
}

/// One line per point, "x y z".
void write_points(std::ostream& out, const PolygonSoup& soup) {
  for (const auto& p : soup.points) {
    write_vertex(out, p);
    out << '\n';
  }
}

/// One line per face, "k i j ..." (0-based), as OFF and PLY hold them (std::to_chars, as the
/// stream would write them).
void write_counted_faces(std::ostream& out, const PolygonSoup& soup) {
  std::string line;
  char number[24];
  for (const auto& f : soup.faces) {
    line.assign(number, std::to_chars(number, number + sizeof(number), f.size()).ptr);
    for (int v : f) {
      line += ' ';
      line.append(number, std::to_chars(number, number + sizeof(number), v).ptr);
    }
    line += '\n';
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
}

void write_off(std::ostream& out, const PolygonSoup& soup) {
  out << "OFF\n" << soup.points.size() << ' ' << soup.faces.size() << " 0\n";
  write_points(out, soup);
  write_counted_faces(out, soup);
}

void write_obj(std::ostream& out, const PolygonSoup& soup) {
  for (const auto& p : soup.points) {
    out << "v ";
    write_vertex(out, p);
    out << '\n';
  }
  for (const auto& f : soup.faces) {
    out << 'f';
    for (int v : f) out << ' ' << v + 1;
    out << '\n';
  }
}

void write_ply(std::ostream& out, const PolygonSoup& soup) {
  out << "ply\nformat ascii 1.0\nelement vertex " << soup.points.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << soup.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  write_points(out, soup);
  write_counted_faces(out, soup);
}

/// STL holds triangles only: polygons are fan-triangulated.
void write_stl(std::ostream& out, const PolygonSoup& soup) {
  out << "solid mesh\n";
  for (const auto& t : fan_triangles(soup).corners) {
    const Eigen::Vector3d &a = soup.points[t[0]], &b = soup.points[t[1]], &c = soup.points[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    out << "facet normal ";
    write_vertex(out, n.allFinite() ? n : Eigen::Vector3d::Zero());
    out << "\n outer loop\n";
    for (const Eigen::Vector3d* p : {&a, &b, &c}) {
      out << "  vertex ";
      write_vertex(out, *p);
      out << '\n';
    }
    out << " endloop\nendfacet\n";
  }
  out << "endsolid mesh\n";
}

}  // namespace

std::string file_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool has_mesh_extension(const std::string& path) {
  const std::string ext = file_extension(path);
  return ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl";
}

void check_mesh_output_path(const std::string& output, const std::vector<std::string>& inputs) {
  check_output_path(output, inputs);
  if (!has_mesh_extension(output)) throw InvalidInput(output + ": " + kUnknownExtension);
}

PolygonSoup read_polygon_soup(const std::string& path) {
  if (!has_mesh_extension(path)) throw InvalidInput(path + ": " + kUnknownExtension);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading");
  PolygonSoup soup;
  if (file_extension(path) == ".off") {
    soup = OffParser(in, path).parse();
  } else {
    if (file_extension(path) == ".ply") check_ply(in, path);
    in.close();
    if (!read_polygon_soup_with_cgal(path, soup))
      throw InvalidInput(path + ": malformed " + file_extension(path).substr(1) + " file");
    validate_soup(soup, path);
  }
  if (soup.faces.empty()) throw InvalidInput(path + ": no faces");
  return soup;
}

Mesh read_mesh(const std::string& path) { return mesh_from_soup(read_polygon_soup(path), path); }

void format_polygon_soup(std::ostream& out, const PolygonSoup& soup, const std::string& path) {
  if (!has_mesh_extension(path)) throw InvalidInput(path + ": " + kUnknownExtension);
  const std::string ext = file_extension(path);
  out.precision(17);
  if (ext == ".off") {
    write_off(out, soup);
  } else if (ext == ".obj") {
    write_obj(out, soup);
  } else if (ext == ".ply") {
    write_ply(out, soup);
  } else {
    write_stl(out, soup);
  }
}

void write_polygon_soup(const PolygonSoup& soup, const std::string& path) {
  if (!has_mesh_extension(path)) throw InvalidInput(path + ": " + kUnknownExtension);
  write_file_atomically(path, [&](std::ostream& out) { format_polygon_soup(out, soup, path); });
}

void write_mesh(const Mesh& mesh, const std::string& path) {
  write_polygon_soup(soup_from_mesh(mesh), path);
}

}  // namespace mg
