#pragma once
/// \file cli_main.h
/// The one place where exceptions become exit codes, shared by every program:
/// 0 success, 1 internal error, 2 bad usage or invalid input, 3 input/output error.
/// Messages go to stderr as one line: `program: message`.

#include "core/atomic_file.h"
#include "core/errors.h"

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

namespace mg {

namespace detail {
inline CLI::Validator number_at_least(double least, bool strict, const char* what) {
  return CLI::Validator(
      [least, strict, what](std::string& text) -> std::string {
        double x = 0;
        try {
          std::size_t used = 0;
          x = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        const bool ok = std::isfinite(x) && (strict ? x > least : x >= least);
        if (!ok) return "must be " + std::string(what) + ", not " + text;
        return {};
      },
      what);
}
}  // namespace detail

/// Option checks with one-line messages (CLI11's own print the largest double as a bound).
inline const CLI::Validator NonNegative = detail::number_at_least(0, false, ">= 0");
inline const CLI::Validator Positive = detail::number_at_least(0, true, "> 0");

template <class Body>
int run_cli(const char* program, Body&& body) {
  try {
    return body();
  } catch (const CLI::CallForHelp&) {
    return 0;  // CLI11 already printed the help
  } catch (const CLI::ParseError& e) {
    std::cerr << program << ": " << e.what() << " (see --help)\n";
    return 2;
  } catch (const InvalidInput& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return 2;
  } catch (const IoError& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return 3;
  } catch (const std::exception& e) {
    std::cerr << program << ": internal error: " << e.what() << '\n';
    return 1;
  }
}

/// Parses the command line, printing help (and throwing CallForHelp) on --help.
inline void parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    throw;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    throw CLI::CallForHelp();
  }
}

/// The `--threads N` option of every program: a limit on TBB's worker threads while the
/// returned object lives (none for N = 0, every core).
inline std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(threads));
}

/// The programs' JSON reports: indented by 2, one trailing newline.
inline void print_json(std::ostream& out, const nlohmann::ordered_json& j) {
  out << std::setw(2) << j << '\n';
}

/// Writes a JSON report through a temporary file renamed at the end. @throws IoError
inline void write_json(const nlohmann::ordered_json& j, const std::string& path) {
  write_file_atomically(path, [&](std::ostream& out) { print_json(out, j); });
}

/// True if the two paths name the same file, whether it exists yet or not (their weakly
/// canonical forms are equal): "out.ma" and "./out.ma" do.
inline bool same_file(const std::string& a, const std::string& b) {
  return std::filesystem::weakly_canonical(a) == std::filesystem::weakly_canonical(b);
}

/// One file of write_files_together(): where, and what fills it.
struct OutputFile {
  std::string path;                          ///< empty: not wanted, skipped
  std::function<void(std::ostream&)> write;  ///< fills the stream (opened in binary mode)
};

/// Writes files that appear together or not at all (a result and its --stats report): each is
/// written to a temporary file beside its target, then all are renamed, in the order given.
/// An exception while writing any of them leaves none; so does a failed rename, which removes
/// the files of this call already renamed (a file they replaced is lost, as on success).
/// @throws IoError naming the target that cannot be opened, written or moved into place
inline void write_files_together(const std::vector<OutputFile>& files) {
  std::vector<std::unique_ptr<AtomicFile>> written;
  std::vector<std::string> targets;
  for (const OutputFile& file : files) {
    if (file.path.empty()) continue;
    written.push_back(std::make_unique<AtomicFile>(file.path));
    targets.push_back(file.path);
    std::ofstream out(written.back()->temp_path(), std::ios::binary);
    if (!out) throw IoError(file.path + ": cannot open for writing");
    file.write(out);
    out.flush();
    if (!out) throw IoError(file.path + ": write failed");
  }
  for (std::size_t i = 0; i < written.size(); ++i) {
    try {
      written[i]->commit();
    } catch (const IoError&) {
      std::error_code ignored;
      for (std::size_t k = 0; k < i; ++k) std::filesystem::remove(targets[k], ignored);
      throw;
    }
  }
}

}  // namespace mg
