#include "core/medial_surface.h"

#include "core/atomic_file.h"
#include "core/errors.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <tuple>
#include <utility>

namespace mg {
namespace {

/// Shortest text that reads back as the same double ("-0.3", "nan", "inf").
std::string format_number(double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

/// Problems with one atom, or empty: shared by the parser (with line numbers) and validate().
std::string atom_problem(const MedialAtom& a) {
  if (!a.centre.allFinite()) return "centre must be finite";
  if (!std::isfinite(a.radius)) return "radius must be finite, got " + format_number(a.radius);
  if (!(a.radius >= 0)) return "radius must be >= 0, got " + format_number(a.radius);
  return {};
}

/// Problem with one edge ("joins atom 3 to itself"), or empty; indices already in range.
std::string edge_problem(const std::array<int, 2>& e) {
  if (e[0] == e[1]) return "joins atom " + std::to_string(e[0]) + " to itself";
  return {};
}

/// Problem with one face ("repeats atom 3"), or empty; indices already in range.
std::string face_problem(const std::array<int, 3>& f) {
  for (int j = 0; j < 3; ++j)
    if (f[j] == f[(j + 1) % 3]) return "repeats atom " + std::to_string(f[j]);
  return {};
}

/// An optionally signed run of decimal digits, of any length: the trailing flag fields
/// (MATFP's `v x y z r TYPE FLAG`, feature flags on `e` and `f` lines).
bool is_integer(const std::string& token) {
  const bool has_sign = !token.empty() && (token[0] == '+' || token[0] == '-');
  std::size_t k = has_sign ? 1 : 0;
  if (k == token.size()) return false;
  for (; k < token.size(); ++k)
    if (token[k] < '0' || token[k] > '9') return false;
  return true;
}

/// One significant line of a text file: its 1-based number and its whitespace-split tokens.
struct Line {
  int number;
  std::vector<std::string> tokens;
};

std::vector<Line> significant_lines(std::istream& in) {
  std::vector<Line> lines;
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    const auto hash = text.find('#');
    if (hash != std::string::npos) text.erase(hash);
    std::istringstream words(text);
    Line line{number, {}};
    for (std::string w; words >> w;) line.tokens.push_back(w);
    if (!line.tokens.empty()) lines.push_back(std::move(line));
  }
  return lines;
}

class Parser {
 public:
  explicit Parser(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const Line& line, const std::string& what) const {
    throw InvalidInput(name_ + ":" + std::to_string(line.number) + ": " + what);
  }

  bool try_real(const std::string& token, double& x) const {
    errno = 0;
    char* end = nullptr;
    x = std::strtod(token.c_str(), &end);
    return end == token.c_str() + token.size() && !token.empty();
  }

  bool try_index(const std::string& token, long& i) const {
    errno = 0;
    char* end = nullptr;
    i = std::strtol(token.c_str(), &end, 10);
    return end == token.c_str() + token.size() && !token.empty() && errno == 0;
  }

  double real(const Line& line, std::size_t k, const char* field) const {
    double x = 0;
    if (!try_real(line.tokens[k], x))
      fail(line, std::string(field) + " is not a number: '" + line.tokens[k] + "'");
    return x;
  }

  int index(const Line& line, std::size_t k, long bound, const char* what) const {
    long i = 0;
    if (!try_index(line.tokens[k], i))
      fail(line, std::string(what) + " index is not an integer: '" + line.tokens[k] + "'");
    if (i < 0 || i >= bound)
      fail(line, std::string(what) + " index " + std::to_string(i) + " out of range [0, " +
                     std::to_string(bound) + ")");
    return static_cast<int>(i);
  }

  /// A `.ma` record: its n required fields (tag included), then any number of integer flags,
  /// which are checked and dropped.
  void expect_fields(const Line& line, std::size_t n, const char* form) const {
    if (line.tokens.size() < n)
      fail(line, "expected '" + std::string(form) + "', got " + std::to_string(line.tokens.size()) +
                     " fields");
    for (std::size_t k = n; k < line.tokens.size(); ++k)
      if (!is_integer(line.tokens[k]))
        fail(line, "field " + std::to_string(k + 1) + " after '" + form +
                       "' is not an integer flag: '" + line.tokens[k] + "'");
  }

  MedialAtom atom(const Line& line, std::size_t first) const {
    static const char* fields[] = {"x", "y", "z", "radius"};
    double v[4];
    for (std::size_t k = 0; k < 4; ++k) v[k] = real(line, first + k, fields[k]);
    MedialAtom a{Eigen::Vector3d(v[0], v[1], v[2]), v[3]};
    const std::string problem = atom_problem(a);
    if (!problem.empty()) fail(line, problem);
    return a;
  }

  MedialSurface parse(std::istream& in) {
    const std::vector<Line> lines = significant_lines(in);
    if (lines.empty()) throw InvalidInput(name_ + ": empty file, no atoms");
    const Line& first = lines.front();
    long counts[3];
    const bool header = first.tokens.size() == 3 && try_index(first.tokens[0], counts[0]) &&
                        try_index(first.tokens[1], counts[1]) &&
                        try_index(first.tokens[2], counts[2]);
    MedialSurface s = header ? parse_ma(lines, counts) : parse_plain(lines);
    if (s.atoms.empty()) throw InvalidInput(name_ + ": no atoms");
    return s;
  }

 private:
  MedialSurface parse_plain(const std::vector<Line>& lines) const {
    MedialSurface s;
    for (const Line& line : lines) {
      if (line.tokens.size() != 4)
        fail(line, "expected a header 'nv ne nf' or an atom 'x y z r', got " +
                       std::to_string(line.tokens.size()) + " fields");
      s.atoms.push_back(atom(line, 0));
    }
    return s;
  }

  MedialSurface parse_ma(const std::vector<Line>& lines, const long counts[3]) const {
    const Line& head = lines.front();
    for (int k = 0; k < 3; ++k)
      if (counts[k] < 0) fail(head, "negative count in header 'nv ne nf'");
    const long nv = counts[0], ne = counts[1], nf = counts[2];
    MedialSurface s;
    // At most one atom per line: a header claiming more fails at the count check, not in an
    // allocation (found by fuzz_ma).
    s.atoms.reserve(std::min(static_cast<std::size_t>(nv), lines.size()));
    for (std::size_t k = 1; k < lines.size(); ++k) {
      const Line& line = lines[k];
      const std::string& tag = line.tokens[0];
      if (tag == "v") {
        expect_fields(line, 5, "v x y z r");
        if (static_cast<long>(s.atoms.size()) == nv)
          fail(line, "more 'v' lines than the header's nv = " + std::to_string(nv));
        s.atoms.push_back(atom(line, 1));
      } else if (tag == "e") {
        expect_fields(line, 3, "e i j");
        if (static_cast<long>(s.edges.size()) == ne)
          fail(line, "more 'e' lines than the header's ne = " + std::to_string(ne));
        const std::array<int, 2> e{index(line, 1, nv, "edge"), index(line, 2, nv, "edge")};
        const std::string problem = edge_problem(e);
        if (!problem.empty()) fail(line, "edge " + problem);
        s.edges.push_back(e);
      } else if (tag == "f") {
        expect_fields(line, 4, "f i j k");
        if (static_cast<long>(s.faces.size()) == nf)
          fail(line, "more 'f' lines than the header's nf = " + std::to_string(nf));
        const std::array<int, 3> f{index(line, 1, nv, "face"), index(line, 2, nv, "face"),
                                   index(line, 3, nv, "face")};
        const std::string problem = face_problem(f);
        if (!problem.empty()) fail(line, "face " + problem);
        s.faces.push_back(f);
      } else {
        fail(line, "unknown record '" + tag + "' (expected v, e or f)");
      }
    }
    auto check_count = [&](const char* what, std::size_t found, long announced) {
      if (static_cast<long>(found) != announced)
        throw InvalidInput(name_ + ": header announces " + std::to_string(announced) + " " + what +
                           ", found " + std::to_string(found));
    };
    check_count("atoms ('v' lines)", s.atoms.size(), nv);
    check_count("edges ('e' lines)", s.edges.size(), ne);
    check_count("faces ('f' lines)", s.faces.size(), nf);
    return s;
  }

  std::string name_;
};

}  // namespace

double characteristic_radius(const MedialSurface& s) {
  double rmin = INFINITY, rmax = 0;
  for (const auto& a : s.atoms) {
    rmin = std::min(rmin, a.radius);
    rmax = std::max(rmax, a.radius);
  }
  return (rmin + rmax) / 2;
}

namespace {

/// The 21 low bits of v spread to every third bit.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1FFFFF;
  v = (v | v << 32) & 0x1F00000000FFFFULL;
  v = (v | v << 16) & 0x1F0000FF0000FFULL;
  v = (v | v << 8) & 0x100F00F00F00F00FULL;
  v = (v | v << 4) & 0x10C30C30C30C30C3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::uint64_t morton_code(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return spread_bits(x) | spread_bits(y) << 1 | spread_bits(z) << 2;
}

MedialSurface spatially_sorted(const MedialSurface& s, std::vector<int>* old_index) {
  const std::size_t n = s.atoms.size();
  Eigen::AlignedBox3d box;
  for (const MedialAtom& a : s.atoms) box.extend(a.centre);
  const double extent = n > 0 ? box.sizes().maxCoeff() : 0;
  const double steps = 2097152;  // 2^21
  std::vector<std::pair<std::uint64_t, int>> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t q[3];
    for (int axis = 0; axis < 3; ++axis) {
      // In [0, steps): NaN (an extent that overflows to infinity) goes to 0.
      const double x = (s.atoms[i].centre[axis] - box.min()[axis]) / extent * steps;
      q[axis] = static_cast<std::uint64_t>(x > 0 ? std::min(x, steps - 1) : 0.0);
    }
    keys[i] = {morton_code(q[0], q[1], q[2]), static_cast<int>(i)};
  }
  std::sort(keys.begin(), keys.end(), [&](const auto& x, const auto& y) {
    if (x.first != y.first) return x.first < y.first;
    const MedialAtom& a = s.atoms[static_cast<std::size_t>(x.second)];
    const MedialAtom& b = s.atoms[static_cast<std::size_t>(y.second)];
    // Then the signs of zeros (-0.0 == 0.0), so that only identical atoms tie.
    auto sign = [](const MedialAtom& m) {
      return std::make_tuple(std::signbit(m.centre.x()), std::signbit(m.centre.y()),
                             std::signbit(m.centre.z()), std::signbit(m.radius));
    };
    return std::make_tuple(a.centre.x(), a.centre.y(), a.centre.z(), a.radius, sign(a), x.second) <
           std::make_tuple(b.centre.x(), b.centre.y(), b.centre.z(), b.radius, sign(b), y.second);
  });
  MedialSurface out;
  out.atoms.reserve(n);
  std::vector<int> new_index(n);
  for (std::size_t k = 0; k < n; ++k) {
    out.atoms.push_back(s.atoms[static_cast<std::size_t>(keys[k].second)]);
    new_index[static_cast<std::size_t>(keys[k].second)] = static_cast<int>(k);
  }
  out.edges.reserve(s.edges.size());
  for (const auto& e : s.edges) out.edges.push_back({new_index[e[0]], new_index[e[1]]});
  out.faces.reserve(s.faces.size());
  for (const auto& f : s.faces)
    out.faces.push_back({new_index[f[0]], new_index[f[1]], new_index[f[2]]});
  if (old_index) {
    old_index->resize(n);
    for (std::size_t k = 0; k < n; ++k) (*old_index)[k] = keys[k].second;
  }
  return out;
}

void validate(const MedialSurface& s) {
  if (s.atoms.empty()) throw InvalidInput("medial surface has no atoms");
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    const std::string problem = atom_problem(s.atoms[i]);
    if (!problem.empty()) throw InvalidInput("atom " + std::to_string(i) + ": " + problem);
  }
  const auto n = static_cast<int>(s.atoms.size());
  auto check = [n](const int* idx, int k, const char* what, std::size_t which) {
    for (int j = 0; j < k; ++j)
      if (idx[j] < 0 || idx[j] >= n)
        throw InvalidInput(std::string(what) + " " + std::to_string(which) + ": index " +
                           std::to_string(idx[j]) + " out of range [0, " + std::to_string(n) + ")");
  };
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    check(s.edges[e].data(), 2, "edge", e);
    const std::string problem = edge_problem(s.edges[e]);
    if (!problem.empty()) throw InvalidInput("edge " + std::to_string(e) + ": " + problem);
  }
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    check(s.faces[f].data(), 3, "face", f);
    const std::string problem = face_problem(s.faces[f]);
    if (!problem.empty()) throw InvalidInput("face " + std::to_string(f) + ": " + problem);
  }
}

MedialSurface parse_medial_surface(std::istream& in, const std::string& name) {
  return Parser(name).parse(in);
}

MedialSurface read_medial_surface(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path + ": cannot open for reading");
  return parse_medial_surface(in, path);
}

void format_medial_surface(std::ostream& out, const MedialSurface& s) {
  out.precision(17);
  out << s.atoms.size() << ' ' << s.edges.size() << ' ' << s.faces.size() << '\n';
  for (const MedialAtom& a : s.atoms)
    out << "v " << a.centre.x() << ' ' << a.centre.y() << ' ' << a.centre.z() << ' ' << a.radius
        << '\n';
  for (const auto& e : s.edges) out << "e " << e[0] << ' ' << e[1] << '\n';
  for (const auto& f : s.faces) out << "f " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
}

void write_medial_surface(const MedialSurface& s, const std::string& path) {
  write_file_atomically(path, [&](std::ostream& out) { format_medial_surface(out, s); });
}

}  // namespace mg
