// libFuzzer target: the mesh readers (read_polygon_soup, then read_mesh's manifold check) on
// arbitrary bytes, as a file of extension MG_FUZZ_EXTENSION (.off is ours; .obj, .ply and .stl
// go through CGAL's readers as we call them). Malformed input must end in mg::InvalidInput;
// anything else escaping, a crash or a sanitizer report is a finding.
#include "core/errors.h"
#include "core/mesh.h"
#include "core/mesh_io.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace {

/// One file per process, rewritten for every input (in /dev/shm when there is one).
const std::string& scratch_path() {
  static const std::string path = [] {
    const char* dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return std::string(dir) + "/mg_fuzz_" + std::to_string(getpid()) + MG_FUZZ_EXTENSION;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = scratch_path();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  if (size > 0) std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    const mg::PolygonSoup soup = mg::read_polygon_soup(path);
    (void)mg::mesh_from_soup(soup, path);
  } catch (const mg::InvalidInput&) {
  }
  std::remove(path.c_str());
  return 0;
}
