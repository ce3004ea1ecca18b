// libFuzzer target: the `.ma` reader (parse_medial_surface) on arbitrary bytes. Malformed input
// must end in mg::InvalidInput (the one exception family); anything else escaping, a crash or a
// sanitizer report is a finding. A file that parses is written and read back: the same surface.
#include "core/errors.h"
#include "core/medial_surface.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  mg::MedialSurface s;
  try {
    s = mg::parse_medial_surface(in, "fuzz.ma");
  } catch (const mg::InvalidInput&) {
    return 0;
  }
  std::ostringstream out;
  mg::format_medial_surface(out, s);
  std::istringstream again(out.str());
  const mg::MedialSurface t = mg::parse_medial_surface(again, "fuzz.ma written");
  if (t.atoms.size() != s.atoms.size() || t.edges != s.edges || t.faces != s.faces) std::abort();
  for (std::size_t i = 0; i < s.atoms.size(); ++i)
    if (t.atoms[i].centre != s.atoms[i].centre || t.atoms[i].radius != s.atoms[i].radius)
      std::abort();
  return 0;
}
