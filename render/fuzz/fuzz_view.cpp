// libFuzzer target: render's view-file reader (parse_view, what read_view and `render --view`
// call) on arbitrary bytes. Malformed input must end in mg::InvalidInput with a one-line message
// naming the file; anything else escaping, a crash or a sanitizer report is a finding. A view
// that parses is valid (validate() passes) and round-trips through its JSON exactly.
#include "core/errors.h"
#include "render/view.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

const std::string kName = "fuzz.json";

mg::render::View parse(const std::string& text) {
  std::istringstream in(text);
  return mg::render::parse_view(in, kName);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mg::render::View view;
  try {
    view = parse(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const mg::InvalidInput& e) {
    const std::string message = e.what();
    if (message.rfind(kName + ": ", 0) != 0 || message.find('\n') != std::string::npos)
      std::abort();  // not one line naming the file
    return 0;
  }
  mg::render::validate(view, kName);
  // What write_view writes, read back: the same view.
  std::ostringstream out;
  mg::render::format_view(out, view);
  const mg::render::View back = parse(out.str());
  if (back.location != view.location || back.look_at != view.look_at || back.sky != view.sky ||
      back.angle != view.angle || back.width != view.width || back.height != view.height)
    std::abort();
  return 0;
}
