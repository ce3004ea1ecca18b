#include "render/run_povray.h"

#include "core/atomic_file.h"
#include "core/errors.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace fs = std::filesystem;

namespace mg::render {
namespace {

constexpr char kPngSignature[] = "\x89PNG\r\n\x1a\n";
constexpr char kSceneFile[] = "scene.pov";
constexpr char kImageFile[] = "image.png";
constexpr char kLogFile[] = "povray.log";

bool is_executable_file(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

/// The path of `program`, looked up on PATH unless it holds a slash. @throws IoError
std::string find_program(const std::string& program) {
  if (program.empty()) throw InvalidInput("the POV-Ray executable name is empty");
  if (program.find('/') != std::string::npos) {
    if (!is_executable_file(program))
      throw IoError("POV-Ray executable '" + program + "' not found or not executable");
    return program;
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + program;
    if (is_executable_file(candidate)) return candidate;
  }
  throw IoError("'" + program +
                "' not found on PATH: install POV-Ray 3.7 (Debian package povray) or name the "
                "executable with --povray");
}

/// A private folder under the system temporary folder, removed with the object.
class WorkFolder {
 public:
  WorkFolder() {
    std::string pattern = (fs::temp_directory_path() / "mg-render-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw IoError(pattern + ": cannot create a temporary folder: " + std::strerror(errno));
    path_ = pattern;
  }
  ~WorkFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  std::string file(const char* name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split_arguments(const std::string& args) {
  std::istringstream in(args);
  std::vector<std::string> out;
  for (std::string a; in >> a;) out.push_back(a);
  return out;
}

/// Runs `program args` in `folder` with stdin from /dev/null and stdout+stderr into `log`.
/// @return the wait status
int run_in(const std::string& program, const std::vector<std::string>& args, const fs::path& folder,
           const std::string& log) {
  std::vector<std::string> argv_text{program};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);

  const pid_t pid = ::fork();
  if (pid < 0)
    throw IoError(std::string("cannot start POV-Ray: fork failed: ") + std::strerror(errno));
  if (pid == 0) {  // child: only async-signal-safe calls until exec
    const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int in = ::open("/dev/null", O_RDONLY);
    if (out < 0 || in < 0 || ::chdir(folder.c_str()) != 0) ::_exit(126);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(out, 2);
    ::execv(argv[0], argv.data());
    const char message[] = "exec failed\n";
    [[maybe_unused]] auto ignored = ::write(2, message, sizeof message - 1);
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR)
      throw IoError(std::string("waiting for POV-Ray failed: ") + std::strerror(errno));
  }
  return status;
}

/// The first error POV-Ray reported (a message wrapped onto lines that start with a space is
/// joined; "Possible ... Error" warnings are skipped), or the last non-empty line of its output.
std::string first_error(std::string log) {
  std::replace(log.begin(), log.end(), '\r', '\n');  // progress lines end in carriage returns
  std::vector<std::string> lines;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    while (!line.empty() && line.back() == ' ') line.pop_back();
    lines.push_back(line);
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.find("rror") == std::string::npos || line.find("Possible") != std::string::npos)
      continue;
    std::string message = line;
    for (std::size_t j = i + 1; j < lines.size() && !lines[j].empty() && lines[j][0] == ' '; ++j)
      message += lines[j];
    return message;
  }
  for (auto it = lines.rbegin(); it != lines.rend(); ++it)
    if (!it->empty()) return *it;
  return "no output";
}

std::uint32_t big_endian(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

}  // namespace

std::string strip_png_metadata(const std::string& bytes, int& width, int& height) {
  const std::size_t signature = sizeof kPngSignature - 1;
  if (bytes.size() < signature || bytes.compare(0, signature, kPngSignature) != 0)
    throw InvalidInput("not a PNG file (no PNG signature)");
  std::string out = bytes.substr(0, signature);
  std::size_t at = signature;
  bool ended = false, has_header = false;
  while (!ended) {
    if (at + 12 > bytes.size()) throw InvalidInput("truncated PNG file");
    const std::uint32_t length = big_endian(bytes, at);
    if (length > bytes.size() - at - 12) throw InvalidInput("truncated PNG file");
    const std::string type = bytes.substr(at + 4, 4);
    if (type == "IHDR" && length >= 8) {
      width = static_cast<int>(big_endian(bytes, at + 8));
      height = static_cast<int>(big_endian(bytes, at + 12));
      has_header = true;
    }
    ended = type == "IEND";
    if (type != "tIME" && type != "tEXt" && type != "zTXt" && type != "iTXt")
      out.append(bytes, at, length + 12);
    at += length + 12;
  }
  if (!has_header) throw InvalidInput("PNG file without IHDR chunk");
  return out;
}

std::string povray_arguments(const std::string& scene_file, const std::string& image_file,
                             int width, int height, const PovrayOptions& opt) {
  std::ostringstream a;
  a << "-D -P +FN8 -UA +W" << width << " +H" << height;
  if (opt.antialias_threshold > 0)
    a << " +AM2 +A" << opt.antialias_threshold << " +R" << opt.antialias_depth << " -J";
  else
    a << " -A";
  if (opt.threads > 0) a << " +WT" << opt.threads;
  a << " +I" << scene_file << " +O" << image_file;
  return a.str();
}

void render_png(const std::string& scene, const std::string& output, int width, int height,
                const PovrayOptions& opt) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InvalidInput("image size must be in [1, 16384] pixels, got " + std::to_string(width) +
                       "x" + std::to_string(height));
  if (!(opt.antialias_threshold >= 0 && opt.antialias_threshold <= 3))
    throw InvalidInput("anti-aliasing threshold must be in [0, 3]");
  if (opt.antialias_depth < 1 || opt.antialias_depth > 9)
    throw InvalidInput("anti-aliasing depth must be in [1, 9]");
  if (opt.threads < 0) throw InvalidInput("POV-Ray threads must be >= 0");
  const std::string program = find_program(opt.executable);

  WorkFolder work;
  {
    std::ofstream out(work.file(kSceneFile), std::ios::binary);
    out << scene;
    if (!out.flush()) throw IoError(work.file(kSceneFile) + ": write failed");
  }
  const int status =
      run_in(program, split_arguments(povray_arguments(kSceneFile, kImageFile, width, height, opt)),
             work.path(), work.file(kLogFile));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                              : "signal " + std::to_string(WTERMSIG(status));
    throw IoError(output + ": POV-Ray (" + program + ") failed (" + how +
                  "): " + first_error(read_file(work.file(kLogFile))));
  }
  const std::string image = read_file(work.file(kImageFile));
  int w = 0, h = 0;
  std::string clean;
  try {
    clean = strip_png_metadata(image, w, h);
  } catch (const InvalidInput& e) {
    throw IoError(output + ": POV-Ray (" + program + ") wrote no valid image (" + e.what() +
                  "): " + first_error(read_file(work.file(kLogFile))));
  }
  if (w != width || h != height)
    throw IoError(output + ": POV-Ray wrote a " + std::to_string(w) + "x" + std::to_string(h) +
                  " image, expected " + std::to_string(width) + "x" + std::to_string(height));

  write_file_atomically(output, [&](std::ostream& out) { out << clean; });
}

}  // namespace mg::render
