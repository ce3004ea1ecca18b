#include "core/atomic_file.h"

#include "core/errors.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace fs = std::filesystem;

namespace mg {
namespace {

std::string temporary_name(const std::string& target) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(target);
  // Keep the extension last: OpenMesh and CGAL writers pick the format from it.
  const std::string tag =
      ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return (p.parent_path() / (p.stem().string() + tag + p.extension().string())).string();
}

}  // namespace

AtomicFile::AtomicFile(std::string target)
    : target_(std::move(target)), temp_(temporary_name(target_)) {}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ignored;
    fs::remove(temp_, ignored);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw IoError(target_ + ": cannot move the finished file into place: " + ec.message());
  committed_ = true;
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary);
    if (!out) throw IoError(path + ": cannot open for writing");
    write(out);
    out.flush();
    if (!out) throw IoError(path + ": write failed");
  }
  file.commit();
}

void check_output_path(const std::string& output, const std::vector<std::string>& inputs) {
  if (output.empty()) throw InvalidInput("output path is empty");
  const fs::path out(output);
  const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InvalidInput(output + ": output folder '" + dir.string() + "' does not exist");
  // Renaming the finished file onto a folder would fail only after all the work.
  if (fs::is_directory(out, ec)) throw InvalidInput(output + ": output path is a folder");
  for (const std::string& in : inputs) {
    if (fs::exists(out, ec) && fs::exists(in, ec) && fs::equivalent(out, in, ec))
      throw InvalidInput(output + ": output would overwrite the input " + in);
  }
}

}  // namespace mg
