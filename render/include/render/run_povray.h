#pragma once
/// \file run_povray.h
/// Runs POV-Ray headless on a scene and writes the PNG atomically and reproducibly.

#include <string>

namespace mg::render {

/// Options of render_png().
struct PovrayOptions {
  std::string executable = "povray";  ///< a name looked up on PATH, or a path
  /// Adaptive anti-aliasing (POV-Ray method 2, jitter off): colour threshold in [0, 3],
  /// 0 switches anti-aliasing off.
  double antialias_threshold = 0.1;
  int antialias_depth = 3;  ///< subdivision depth of method 2 (POV-Ray +R), 1..9
  int threads = 0;          ///< POV-Ray render threads, 0 = POV-Ray's default (every core)
};

/// The POV-Ray command-line arguments (after the program name) render_png() uses for
/// `scene_file` -> `image_file`: no display (-D), PNG (+FN), no alpha, no pause, size, adaptive
/// anti-aliasing without jitter (+AM2 -J: deterministic), threads.
std::string povray_arguments(const std::string& scene_file, const std::string& image_file,
                             int width, int height, const PovrayOptions& opt = {});

/// Renders `scene` (POV-Ray text) into the PNG `output`, width x height pixels.
/// POV-Ray runs in a private temporary folder (its default I/O restrictions allow the current
/// folder), its output is checked (PNG signature, size) and stripped of its time-stamp chunks
/// (tIME, tEXt, zTXt, iTXt: POV-Ray writes the render date), then written through a temporary
/// file renamed onto `output`: the same scene gives the same bytes, and a failure leaves no
/// file.
/// @pre width, height in [1, 16384]; options in their documented ranges
/// @throws InvalidInput on bad sizes or options; IoError if POV-Ray is not found, fails
///         (message: its exit status and first error line) or writes no valid image, or if
///         `output` cannot be written
void render_png(const std::string& scene, const std::string& output, int width, int height,
                const PovrayOptions& opt = {});

/// The PNG `bytes` without their tIME, tEXt, zTXt and iTXt chunks; the pixel size from the
/// IHDR chunk into width and height.
/// @throws InvalidInput if `bytes` is not a well-formed PNG chunk sequence
std::string strip_png_metadata(const std::string& bytes, int& width, int& height);

}  // namespace mg::render
