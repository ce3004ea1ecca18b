#pragma once
/// \file atomic_file.h
/// Output files that appear complete or not at all, and a guard against overwriting inputs.

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace mg {

/// A temporary file next to `target`, with the same extension (writers that choose the format
/// by extension still work). commit() renames it onto `target`; the destructor removes it if
/// commit() was never called, so an exception leaves no partial output.
class AtomicFile {
 public:
  explicit AtomicFile(std::string target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Where to write.
  const std::string& temp_path() const { return temp_; }
  /// Renames the temporary file onto the target. @throws IoError
  void commit();

 private:
  std::string target_;
  std::string temp_;
  bool committed_ = false;
};

/// Writes `path` through an AtomicFile: `write` fills the stream (opened in binary mode); an
/// exception from `write` or a failed stream leaves no file.
/// @throws IoError if the file cannot be opened, written or moved into place
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

/// @throws InvalidInput if `output` names the same file as one of `inputs` (never overwrite an
/// input), names a folder, or if `output`'s folder does not exist.
void check_output_path(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace mg
