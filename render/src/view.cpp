#include "render/view.h"

#include "core/atomic_file.h"
#include "core/errors.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>

namespace mg::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

double radians(double degrees) { return degrees * kPi / 180.0; }

/// Right and up of a camera looking along `forward` (unit) with `sky`: right = forward x sky.
void camera_frame(const Eigen::Vector3d& forward, const Eigen::Vector3d& sky,
                  Eigen::Vector3d& right, Eigen::Vector3d& up) {
  right = forward.cross(sky).normalized();
  up = right.cross(forward);
}

bool parallel(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return !(a.normalized().cross(b.normalized()).norm() > 1e-9);
}

Eigen::Vector3d vector_field(const nlohmann::json& j, const char* key, const std::string& name) {
  if (!j.contains(key)) throw InvalidInput(name + ": missing \"" + key + "\"");
  const auto& v = j.at(key);
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    throw InvalidInput(name + ": \"" + key + "\" must be an array of 3 numbers");
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

double number_field(const nlohmann::json& j, const char* key, const std::string& name) {
  if (!j.contains(key) || !j.at(key).is_number())
    throw InvalidInput(name + ": \"" + key + "\" must be a number");
  return j.at(key).get<double>();
}

int size_field(const nlohmann::json& j, const char* key, const std::string& name) {
  if (!j.contains(key) || !j.at(key).is_number_integer())
    throw InvalidInput(name + ": \"" + key + "\" must be an integer");
  const nlohmann::json& v = j.at(key);
  // Integers above 2^63 are stored unsigned: read as signed they would wrap.
  const bool in_range = v.is_number_unsigned()
                            ? v.get<std::uint64_t>() >= 1 && v.get<std::uint64_t>() <= 16384
                            : v.get<std::int64_t>() >= 1 && v.get<std::int64_t>() <= 16384;
  if (!in_range)
    throw InvalidInput(name + ": \"" + key + "\" must be in [1, 16384], got " + v.dump());
  return v.get<int>();
}

}  // namespace

void validate(const View& view, const std::string& name) {
  if (!view.location.allFinite() || !view.look_at.allFinite() || !view.sky.allFinite())
    throw InvalidInput(name + ": camera vectors must be finite");
  if (!((view.look_at - view.location).norm() > 0))
    throw InvalidInput(name + ": location and look_at coincide");
  if (!(view.sky.norm() > 0)) throw InvalidInput(name + ": sky must be non-zero");
  if (parallel(view.look_at - view.location, view.sky))
    throw InvalidInput(name + ": sky is parallel to the line of sight");
  if (!(view.angle > 0 && view.angle < 180))
    throw InvalidInput(name + ": angle must be in (0, 180) degrees, got " +
                       std::to_string(view.angle));
  if (view.width < 1 || view.height < 1 || view.width > 16384 || view.height > 16384)
    throw InvalidInput(name + ": image size must be in [1, 16384] pixels, got " +
                       std::to_string(view.width) + "x" + std::to_string(view.height));
}

View frame_view(const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& radii,
                int width, int height, const FramingOptions& opt) {
  if (centres.empty()) throw InvalidInput("frame_view: nothing to frame");
  if (!radii.empty() && radii.size() != centres.size())
    throw InvalidInput("frame_view: " + std::to_string(radii.size()) + " radii for " +
                       std::to_string(centres.size()) + " centres");
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const double r = radii.empty() ? 0.0 : radii[i];
    if (!centres[i].allFinite() || !std::isfinite(r) || !(r >= 0))
      throw InvalidInput("frame_view: ball " + std::to_string(i) +
                         " is not finite or has a negative radius");
    box.extend(centres[i] - Eigen::Vector3d::Constant(r));
    box.extend(centres[i] + Eigen::Vector3d::Constant(r));
  }
  const double diagonal = box.diagonal().norm();
  if (!(diagonal > 0)) throw InvalidInput("frame_view: the object has zero size");
  if (width < 1 || height < 1)
    throw InvalidInput("frame_view: image size must be positive, got " + std::to_string(width) +
                       "x" + std::to_string(height));
  if (!opt.direction.allFinite() || !(opt.direction.norm() > 0))
    throw InvalidInput("frame_view: direction must be a finite non-zero vector");
  if (!opt.sky.allFinite() || !(opt.sky.norm() > 0))
    throw InvalidInput("frame_view: sky must be a finite non-zero vector");
  if (parallel(opt.direction, opt.sky))
    throw InvalidInput("frame_view: direction is parallel to sky");
  if (!(opt.angle > 0 && opt.angle < 180))
    throw InvalidInput("frame_view: angle must be in (0, 180) degrees");
  if (!(opt.margin >= 0 && opt.margin < 0.5))
    throw InvalidInput("frame_view: margin must be in [0, 0.5)");

  const Eigen::Vector3d back = opt.direction.normalized();  // towards the eye
  Eigen::Vector3d right, up;
  camera_frame(-back, opt.sky, right, up);
  const double tan_h = std::tan(radians(opt.angle) / 2) * (1 - opt.margin);
  const double tan_v = std::tan(radians(opt.angle) / 2) * height / width * (1 - opt.margin);
  // 1 / sin of the half angles: a ball of radius r is inside a side plane of the view frustum
  // when its centre is at least r from it.
  const double ball_h = std::sqrt(1 + tan_h * tan_h) / tan_h;
  const double ball_v = std::sqrt(1 + tan_v * tan_v) / tan_v;
  const Eigen::Vector3d centre = box.center();
  // Eye at centre + d * back. A point q (relative to the centre) is in the image if
  // |q.right| <= tan_h * (d - q.back) and |q.up| <= tan_v * (d - q.back).
  double d = 0.0, nearest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const Eigen::Vector3d q = centres[i] - centre;
    const double r = radii.empty() ? 0.0 : radii[i];
    const double z = q.dot(back);
    nearest = std::max(nearest, z + r);
    d = std::max({d, z + std::abs(q.dot(right)) / tan_h + r * ball_h,
                  z + std::abs(q.dot(up)) / tan_v + r * ball_v});
  }
  d = std::max(d, nearest + 0.01 * diagonal);  // never inside the object (seen edge-on)

  View view;
  view.look_at = centre;
  view.location = centre + d * back;
  view.sky = opt.sky.normalized();
  view.angle = opt.angle;
  view.width = width;
  view.height = height;
  return view;
}

View frame_view(const Eigen::AlignedBox3d& box, int width, int height, const FramingOptions& opt) {
  if (box.isEmpty()) throw InvalidInput("frame_view: the bounding box is empty");
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  return frame_view(corners, {}, width, height, opt);
}

Eigen::Vector3d project(const View& view, const Eigen::Vector3d& point) {
  const Eigen::Vector3d forward = (view.look_at - view.location).normalized();
  Eigen::Vector3d right, up;
  camera_frame(forward, view.sky, right, up);
  const Eigen::Vector3d q = point - view.location;
  const double depth = q.dot(forward);
  const double tan_h = std::tan(radians(view.angle) / 2);
  const double tan_v = tan_h * view.height / view.width;
  const double x = q.dot(right) / (depth * tan_h);  // -1 .. 1 across the image
  const double y = q.dot(up) / (depth * tan_v);
  return {(x + 1) / 2 * view.width, (1 - y) / 2 * view.height, depth};
}

View parse_view(std::istream& in, const std::string& name) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);  // strict: nothing but white space after the object
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(name + ": not a JSON view file (" + std::string(e.what()) + ")");
  }
  if (!j.is_object()) throw InvalidInput(name + ": a view file holds one JSON object");
  View view;
  view.location = vector_field(j, "location", name);
  view.look_at = vector_field(j, "look_at", name);
  view.sky = vector_field(j, "sky", name);
  view.angle = number_field(j, "angle", name);
  view.width = size_field(j, "width", name);
  view.height = size_field(j, "height", name);
  validate(view, name);
  return view;
}

View read_view(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path + ": cannot open for reading");
  return parse_view(in, path);
}

void format_view(std::ostream& out, const View& view) {
  nlohmann::ordered_json j;
  auto array = [](const Eigen::Vector3d& v) {
    return nlohmann::json::array({v.x(), v.y(), v.z()});
  };
  j["location"] = array(view.location);
  j["look_at"] = array(view.look_at);
  j["sky"] = array(view.sky);
  j["angle"] = view.angle;
  j["width"] = view.width;
  j["height"] = view.height;
  out << std::setw(2) << j << '\n';
}

void write_view(const View& view, const std::string& path) {
  validate(view, path);
  write_file_atomically(path, [&](std::ostream& out) { format_view(out, view); });
}

}  // namespace mg::render
