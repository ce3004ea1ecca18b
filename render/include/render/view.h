#pragma once
/// \file view.h
/// The camera of a render, framed once on a reference object and reusable from a JSON file, so
/// that every column of a figure (original, union of spheres, garbing mesh) lines up.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <iosfwd>
#include <string>
#include <vector>

namespace mg::render {

/// A perspective camera and the image size it was framed for. Model units, right-handed
/// coordinates; the image's right is (look_at - location) x sky.
struct View {
  Eigen::Vector3d location = Eigen::Vector3d::Zero();   ///< eye, model units
  Eigen::Vector3d look_at = -Eigen::Vector3d::UnitZ();  ///< point seen at the image centre
  Eigen::Vector3d sky = Eigen::Vector3d::UnitY();       ///< up in the image (unit vector)
  double angle = 30.0;  ///< horizontal field of view, degrees in (0, 180)
  int width = 800;      ///< pixels
  int height = 600;     ///< pixels
};

/// Options of frame_view().
struct FramingOptions {
  /// From the object towards the eye (any length): front (+z), a little right (+x) and above
  /// (+y), i.e. 24 degrees of elevation and 27 of azimuth.
  Eigen::Vector3d direction{0.5, 0.5, 1.0};
  Eigen::Vector3d sky = Eigen::Vector3d::UnitY();  ///< up in the image
  double angle = 30.0;                             ///< horizontal field of view, degrees
  double margin = 0.05;  ///< free border, fraction of the image half-width/height, in [0, 0.5)
};

/// The camera that looks at the centre of the balls' bounding box from `opt.direction` and is
/// just far enough for every ball to lie inside the image with the requested margin: the
/// object fills the frame along its longer projected extent (exactly, for a perspective view).
/// @param centres ball centres, model units
/// @param radii   ball radii, model units, >= 0; empty = all 0 (points, e.g. mesh vertices)
/// @pre centres non-empty and finite, radii finite and >= 0 (as many as centres, or none), the
///      bounding box not a single point; width, height >= 1; direction non-zero and not
///      parallel to sky; angle in (0, 180); margin in [0, 0.5)
/// @throws InvalidInput naming the offending parameter
View frame_view(const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& radii,
                int width, int height, const FramingOptions& opt = {});

/// frame_view() of the eight corners of `box`.
View frame_view(const Eigen::AlignedBox3d& box, int width, int height,
                const FramingOptions& opt = {});

/// Checks a view: finite vectors, location != look_at, sky not parallel to the line of sight,
/// angle in (0, 180), width and height >= 1.
/// @param name used in messages (a file name)
/// @throws InvalidInput naming the first problem
void validate(const View& view, const std::string& name);

/// Parses a view file's text (one JSON object: location, look_at, sky, angle, width, height;
/// nothing but white space after it) and validates it.
/// @param name used in messages: `name: problem`, one line
/// @throws InvalidInput if the text is not such an object or the view is invalid
View parse_view(std::istream& in, const std::string& name);

/// Reads a view written by write_view() (see parse_view).
/// @throws IoError if the file cannot be opened; InvalidInput if it is malformed or invalid
View read_view(const std::string& path);

/// Formats a view as write_view() writes it: JSON, 17 significant digits (parse_view() reads it
/// back exactly).
void format_view(std::ostream& out, const View& view);

/// Writes a view (format_view) through a temporary file renamed at the end.
/// @throws InvalidInput if the view is invalid; IoError
void write_view(const View& view, const std::string& path);

/// Pixel coordinates (x right, y down, pixel centres at +0.5) where `point` appears in the
/// image of `view`, and its depth along the line of sight (model units; > 0 in front).
Eigen::Vector3d project(const View& view, const Eigen::Vector3d& point);

}  // namespace mg::render
