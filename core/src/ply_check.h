#pragma once
// Internal to mg::mesh: the PLY check run before CGAL's reader sees a file.

#include <iosfwd>
#include <string>

namespace mg {

/// Checks a PLY file's header and body before CGAL's reader sees it. CGAL's reader has
/// undefined behaviour (found by fuzz_ply) on a `property` line before any `element` line (read
/// out of an empty vector), on coordinates x, y, z that are not float or double, and on vertex
/// indices that are not a list of integers (a null pointer from a failed cast); and it sizes
/// buffers by the file's own counts, so a 200-byte file announcing 2^31 rows or a list of 2^31
/// items made it allocate up to 16 GB. Here every element's rows must fit in the bytes left (at
/// least 2 bytes per value in ASCII, the fixed size in binary), and every row is walked: each
/// list count must be a non-negative value of its type whose items fit in the bytes left, each
/// ASCII value a whole number of its type. What passes, CGAL reads within the file's size.
/// @param in    the file, opened in binary mode at its start; left anywhere
/// @param path  used in messages: `path:line: problem` in the header, `path: problem` after it
/// @throws InvalidInput naming the first problem
void check_ply(std::istream& in, const std::string& path);

}  // namespace mg
