#include "ply_check.h"

#include "core/errors.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <istream>
#include <sstream>
#include <string>
#include <vector>

namespace mg {
namespace {

/// A PLY value type (the eight CGAL reads): its names, its size in a binary body, and the
/// range of an integer type.
struct PlyType {
  const char* name;
  const char* alias;
  int bytes;
  bool integer;
  long long lowest, highest;  ///< integer types only
};

constexpr PlyType kPlyTypes[] = {
    {"char", "int8", 1, true, -128, 127},
    {"uchar", "uint8", 1, true, 0, 255},
    {"short", "int16", 2, true, -32768, 32767},
    {"ushort", "uint16", 2, true, 0, 65535},
    {"int", "int32", 4, true, -2147483648LL, 2147483647LL},
    {"uint", "uint32", 4, true, 0, 4294967295LL},
    {"float", "float32", 4, false, 0, 0},
    {"double", "float64", 8, false, 0, 0},
};

const PlyType* find_type(const std::string& name) {
  for (const PlyType& t : kPlyTypes)
    if (name == t.name || name == t.alias) return &t;
  return nullptr;
}

struct PlyProperty {
  const PlyType* type = nullptr;   ///< a scalar's type, a list's item type
  const PlyType* count = nullptr;  ///< a list's count type; null for a scalar
};

struct PlyElement {
  std::string name;
  std::uint64_t rows = 0;
  int line = 0;  ///< of its `element` line
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
};

/// The header, up to and including its end_header line.
PlyHeader read_header(std::istream& in, const std::string& path) {
  PlyHeader header;
  std::string text;
  int line = 0;
  auto fail = [&](const std::string& problem) {
    throw InvalidInput(path + ":" + std::to_string(line) + ": " + problem);
  };
  while (std::getline(in, text)) {
    ++line;
    std::istringstream words(text);
    std::string keyword;
    words >> keyword;
    if (line == 1) {
      if (keyword != "ply") fail("expected the PLY magic 'ply'");
      continue;
    }
    if (line == 2) {
      std::string format, version;
      words >> format >> version;
      if (keyword != "format" || version.empty())
        fail("expected 'format ascii|binary_little_endian|binary_big_endian VERSION'");
      if (format == "ascii") {
        header.format = PlyFormat::ascii;
      } else if (format == "binary_little_endian") {
        header.format = PlyFormat::binary_little_endian;
      } else if (format == "binary_big_endian") {
        header.format = PlyFormat::binary_big_endian;
      } else {
        fail("unknown PLY format '" + format + "'");
      }
      continue;
    }
    if (keyword == "end_header") return header;
    if (keyword == "element") {
      PlyElement e;
      std::string rows;
      words >> e.name >> rows;
      e.line = line;
      const char* end = rows.data() + rows.size();
      const auto [stop, error] = std::from_chars(rows.data(), end, e.rows);
      if (e.name.empty() || rows.empty() || error != std::errc() || stop != end)
        fail("expected 'element NAME COUNT', the count an integer from 0 to 2^64 - 1");
      header.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (header.elements.empty()) fail("a property before any element");
      std::string type, count_type, name;
      words >> type;
      const bool list = type == "list";
      if (list) words >> count_type >> type;
      words >> name;
      if (name.empty()) fail("expected 'property TYPE NAME' or 'property list COUNT TYPE NAME'");
      PlyProperty p;
      p.type = find_type(type);
      if (list) p.count = find_type(count_type);
      // CGAL's reader dereferences a failed cast on these two (found by fuzz_ply).
      if ((name == "x" || name == "y" || name == "z") && (list || !p.type || p.type->integer))
        fail("coordinate '" + name + "' must be float or double, got '" + (list ? "list" : type) +
             "'");
      if ((name == "vertex_indices" || name == "vertex_index") &&
          (!list || !p.count || !p.count->integer || !p.type || !p.type->integer))
        fail("'" + name + "' must be a list of integers");
      if (!p.type) fail("unknown PLY property type '" + type + "'");
      if (list && (!p.count || !p.count->integer))
        fail("a list count must be of an integer type, got '" + count_type + "'");
      header.elements.back().properties.push_back(p);
    } else if (keyword != "format" && keyword != "comment" && keyword != "obj_info") {
      fail("unknown PLY header keyword '" + keyword + "'");
    }
  }
  fail("the header has no end_header");
  return header;
}

/// Walks the body: every row of every element, as CGAL's reader will read it.
class BodyWalker {
 public:
  BodyWalker(std::istream& in, const std::string& path, PlyFormat format, std::uint64_t left)
      : in_(in), path_(path), format_(format), left_(left) {}

  void walk(const PlyElement& e) {
    element_ = &e;
    if (e.rows == 0) return;
    if (e.properties.empty())
      fail_header("element '" + e.name + "' announces " + std::to_string(e.rows) +
                  " rows but has no properties");
    // The fewest bytes a row takes: in ASCII a character and a separator per value (but
    // the file's last), in binary each scalar and each list's count.
    const bool ascii = format_ == PlyFormat::ascii;
    std::uint64_t least = 0;
    bool lists = false;
    for (const PlyProperty& p : e.properties) {
      least += ascii ? 2 : static_cast<std::uint64_t>(p.count ? p.count->bytes : p.type->bytes);
      lists = lists || p.count;
    }
    const std::uint64_t room = (left_ + (ascii ? 1 : 0)) / least;
    if (e.rows > room)
      fail_header("element '" + e.name + "' announces " + std::to_string(e.rows) +
                  " rows, but the " + std::to_string(left_) + " bytes left hold at most " +
                  std::to_string(room));
    if (!ascii && !lists) {  // fixed-size rows: they fit
      in_.seekg(static_cast<std::streamoff>(e.rows * least), std::ios::cur);
      left_ -= e.rows * least;
      return;
    }
    for (row_ = 0; row_ < e.rows; ++row_)
      for (const PlyProperty& p : e.properties) {
        if (!p.count) {
          value(*p.type);
          continue;
        }
        const long long n = value(*p.count);
        if (n < 0) fail("list count " + std::to_string(n) + " is negative");
        if (ascii) {
          for (long long k = 0; k < n; ++k) value(*p.type);
        } else {
          const std::uint64_t bytes = static_cast<std::uint64_t>(n) * p.type->bytes;
          if (bytes > left_)
            fail("list count " + std::to_string(n) + " needs " + std::to_string(bytes) +
                 " bytes, " + std::to_string(left_) + " are left");
          skip(bytes);
        }
      }
  }

 private:
  /// One value: an integer's value (0 for a real), checked as CGAL will read it.
  long long value(const PlyType& type) {
    if (format_ != PlyFormat::ascii) {
      if (static_cast<std::uint64_t>(type.bytes) > left_) fail_end();
      if (!type.integer) {
        skip(static_cast<std::uint64_t>(type.bytes));
        return 0;
      }
      unsigned char b[4] = {0, 0, 0, 0};
      in_.read(reinterpret_cast<char*>(b), type.bytes);
      left_ -= static_cast<std::uint64_t>(type.bytes);
      if (!in_) fail_end();
      std::uint32_t u = 0;
      for (int i = 0; i < type.bytes; ++i) {
        const int k = format_ == PlyFormat::binary_little_endian ? type.bytes - 1 - i : i;
        u = (u << 8) | b[k];
      }
      // Two's complement: a signed type's top bit is its sign.
      const long long v = static_cast<long long>(u);
      const long long span = type.highest - type.lowest + 1;
      return type.lowest < 0 && v > type.highest ? v - span : v;
    }
    if (!next_token()) fail_end();
    if (type.integer) {
      const char* first = token_.data() + (token_[0] == '+' ? 1 : 0);
      const char* end = token_.data() + token_.size();
      long long v = 0;
      const auto [stop, error] = std::from_chars(first, end, v);
      if (first == end || (*first == '-' && token_[0] == '+') || error != std::errc() ||
          stop != end || v < type.lowest || v > type.highest)
        fail_value(type);
      return v;
    }
    // CGAL reads a real from these characters only, then sscanf's %lf.
    const bool characters = token_.find_first_not_of("0123456789.eE+-") == std::string::npos;
    char* stop = nullptr;
    std::strtod(token_.c_str(), &stop);
    if (!characters || stop != token_.c_str() + token_.size()) fail_value(type);
    return 0;
  }

  /// The next white-space separated word of an ASCII body into token_; false at the end.
  bool next_token() {
    std::streambuf& b = *in_.rdbuf();
    const auto eof = std::char_traits<char>::eof();
    auto space = [](int c) { return c == ' ' || (c >= '\t' && c <= '\r'); };
    int c = b.sgetc();
    for (; c != eof && space(c); c = b.snextc()) --left_;
    token_.clear();
    for (; c != eof && !space(c); c = b.snextc()) {
      token_ += static_cast<char>(c);
      --left_;
    }
    return !token_.empty();
  }

  void skip(std::uint64_t bytes) {
    in_.ignore(static_cast<std::streamsize>(bytes));
    left_ -= bytes;
  }

  [[noreturn]] void fail_header(const std::string& problem) const {
    throw InvalidInput(path_ + ":" + std::to_string(element_->line) + ": " + problem);
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw InvalidInput(path_ + ": element '" + element_->name + "' row " + std::to_string(row_) +
                       ": " + problem);
  }
  [[noreturn]] void fail_end() const {
    throw InvalidInput(path_ + ": the file ends in row " + std::to_string(row_) + " of element '" +
                       element_->name + "' (" + std::to_string(element_->rows) + " announced)");
  }
  [[noreturn]] void fail_value(const PlyType& type) const {
    fail("'" + token_.substr(0, 40) + (token_.size() > 40 ? "..." : "") + "' is not a " +
         type.name);
  }

  std::istream& in_;
  const std::string& path_;
  PlyFormat format_;
  std::uint64_t left_;  ///< bytes of the file after the current position
  const PlyElement* element_ = nullptr;
  std::uint64_t row_ = 0;
  std::string token_;
};

}  // namespace

void check_ply(std::istream& in, const std::string& path) {
  const PlyHeader header = read_header(in, path);
  const std::streamoff body = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  in.seekg(body);
  if (body < 0 || end < body || !in) throw InvalidInput(path + ": cannot measure the PLY body");
  BodyWalker walker(in, path, header.format, static_cast<std::uint64_t>(end - body));
  for (const PlyElement& e : header.elements) walker.walk(e);
}

}  // namespace mg
