#include "render/povray_scene.h"

#include "core/errors.h"
#include "core/mesh_io.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>

namespace mg::render {
namespace {

/// Appends numbers locale-independently: exact (shortest round trip) or with a few digits.
class Text {
 public:
  Text& operator<<(const std::string& s) {
    out_ += s;
    return *this;
  }
  Text& operator<<(const char* s) {
    out_ += s;
    return *this;
  }
  Text& operator<<(char c) {
    out_ += c;
    return *this;
  }
  Text& operator<<(long long i) { return append(i); }
  Text& operator<<(int i) { return append(i); }
  Text& operator<<(std::size_t i) { return append(i); }
  Text& operator<<(double x) {  // exact: reads back as the same double
    char buffer[32];
    out_.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, x).ptr);
    return *this;
  }
  /// `x` with `digits` significant digits (colours, normals).
  Text& rounded(double x, int digits) {
    char buffer[32];
    out_.append(
        buffer,
        std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, digits).ptr);
    return *this;
  }
  Text& vector(const Eigen::Vector3d& v) {
    return *this << '<' << v.x() << ", " << v.y() << ", " << v.z() << '>';
  }
  Text& rounded_vector(const Eigen::Vector3d& v, int digits) {
    *this << '<';
    rounded(v.x(), digits) << ", ";
    rounded(v.y(), digits) << ", ";
    rounded(v.z(), digits) << '>';
    return *this;
  }
  std::string take() { return std::move(out_); }

 private:
  template <class Int>
  Text& append(Int i) {
    out_ += std::to_string(i);
    return *this;
  }
  std::string out_;
};

/// The camera's frame: forward (unit, towards look_at), right, up (right-handed model space).
struct Frame {
  Eigen::Vector3d forward, right, up;
  double distance;
};

Frame frame_of(const View& view) {
  Frame f;
  f.forward = view.look_at - view.location;
  f.distance = f.forward.norm();
  f.forward /= f.distance;
  f.right = f.forward.cross(view.sky).normalized();
  f.up = f.right.cross(f.forward);
  return f;
}

/// Mesh colours by rank among the scene's meshes (linear RGB): clay, blue, green, rose.
const std::array<Eigen::Vector3d, 4> kMeshPalette = {
    Eigen::Vector3d(0.80, 0.72, 0.58), Eigen::Vector3d(0.42, 0.60, 0.85),
    Eigen::Vector3d(0.52, 0.78, 0.46), Eigen::Vector3d(0.86, 0.50, 0.50)};

void write_mesh(Text& out, const PolygonSoup& soup, const std::string& name, int rank,
                const SceneOptions& opt) {
  if (soup.faces.empty()) throw InvalidInput(name + ": mesh has no face");
  validate_soup(soup, name);
  ShadingNormals normals;
  try {
    normals = shading_normals(soup, opt.normals);
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }

  // Fan triangles of every face, with their corner normals; triangles of zero area are left
  // out (POV-Ray drops them with a warning anyway).
  struct Triangle {
    std::array<int, 3> v, n;
  };
  std::vector<Triangle> triangles;
  const Triangles fan = fan_triangles(soup);
  for (std::size_t k = 0; k < fan.corners.size(); ++k) {
    const auto& t = fan.corners[k];
    const Eigen::Vector3d& a = soup.points[t[0]];
    if ((soup.points[t[1]] - a).cross(soup.points[t[2]] - a).squaredNorm() == 0) continue;
    const auto& c = normals.corners[fan.face[k]];
    const int i = fan.fan[k];
    triangles.push_back({t, {c[0], c[i], c[i + 1]}});
  }
  if (triangles.empty()) throw InvalidInput(name + ": every face of the mesh has zero area");

  out << "// mesh " << rank << ": " << name << " (" << soup.points.size() << " vertices, "
      << soup.faces.size() << " faces, " << triangles.size() << " triangles, "
      << (opt.flat_shading ? "flat" : "smooth") << " shading)\n";
  out << "mesh2 {\n  vertex_vectors { " << soup.points.size();
  for (const auto& p : soup.points) {
    out << ",\n    ";
    out.vector(p);
  }
  out << "}\n";
  if (!opt.flat_shading) {
    out << "  normal_vectors { " << normals.normals.size();
    for (const auto& n : normals.normals) {
      out << ",\n    ";
      out.rounded_vector(n, 7);
    }
    out << "}\n";
  }
  out << "  face_indices { " << triangles.size();
  for (const auto& t : triangles)
    out << ",\n    <" << t.v[0] << ", " << t.v[1] << ", " << t.v[2] << '>';
  out << "}\n";
  if (!opt.flat_shading && !normals.per_vertex) {
    out << "  normal_indices { " << triangles.size();
    for (const auto& t : triangles)
      out << ",\n    <" << t.n[0] << ", " << t.n[1] << ", " << t.n[2] << '>';
    out << "}\n";
  }
  const Eigen::Vector3d& c = kMeshPalette[rank % kMeshPalette.size()];
  out << "  texture { pigment { rgbt <" << c.x() << ", " << c.y() << ", " << c.z() << ", "
      << opt.mesh_transmit << "> } finish { mg_finish } }\n";
  // Smooth triangles shadowing their neighbours draw a jagged line along the shadow terminator;
  // a smooth mesh therefore casts no shadow (flat and sphere geometry keeps its shadows).
  if (!opt.flat_shading) out << "  no_shadow\n";
  out << "}\n";
}

void write_medial_surface(Text& out, const MedialSurface& s, const std::string& name, int rank,
                          const SceneOptions& opt) {
  try {
    validate(s);
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
  double lo = s.atoms[0].radius, hi = lo;
  for (const auto& a : s.atoms) {
    lo = std::min(lo, a.radius);
    hi = std::max(hi, a.radius);
  }
  const int levels = opt.colour_levels;
  const std::string prefix = "mg_atoms" + std::to_string(rank) + "_";
  out << "// medial surface " << rank << ": " << name << " (" << s.atoms.size()
      << " atoms as spheres; radius " << lo << " (red) to " << hi << " (blue), " << levels
      << " colour levels)\n";
  std::vector<bool> used(levels, false);
  std::vector<int> level(s.atoms.size());
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    const double t = hi > lo ? (s.atoms[i].radius - lo) / (hi - lo) : 0.5;
    level[i] = static_cast<int>(std::lround(t * (levels - 1)));
    used[level[i]] = true;
  }
  for (int l = 0; l < levels; ++l) {
    if (!used[l]) continue;
    out << "#declare " << prefix << l << " = texture { pigment { rgb ";
    out.rounded_vector(radius_colour(static_cast<double>(l) / (levels - 1)), 6);
    out << " } finish { mg_finish } }\n";
  }
  // The union of the balls, written as separate spheres: POV-Ray's bounding hierarchy then
  // covers every sphere (it does not split unions by default), and opaque spheres look the same.
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    out << "sphere { ";
    out.vector(s.atoms[i].centre) << ", " << s.atoms[i].radius << " texture { " << prefix
                                  << level[i] << " } }\n";
  }
}

}  // namespace

bool has_medial_extension(const std::string& path) {
  const std::string ext = file_extension(path);
  return ext == ".ma" || ext == ".xyzr";
}

SceneObject read_scene_object(const std::string& path) {
  SceneObject object;
  object.name = path;
  if (has_medial_extension(path))
    object.geometry = read_medial_surface(path);
  else if (has_mesh_extension(path))
    object.geometry = read_polygon_soup(path);
  else
    throw InvalidInput(path +
                       ": unknown extension (expected a mesh .off .obj .ply .stl or a "
                       "medial surface .ma .xyzr)");
  return object;
}

Eigen::AlignedBox3d bounding_box(const SceneObject& object) {
  Eigen::AlignedBox3d box;  // empty
  if (const auto* soup = std::get_if<PolygonSoup>(&object.geometry)) {
    for (const auto& p : soup->points) box.extend(p);
  } else {
    for (const auto& a : std::get<MedialSurface>(object.geometry).atoms) {
      box.extend(a.centre - Eigen::Vector3d::Constant(a.radius));
      box.extend(a.centre + Eigen::Vector3d::Constant(a.radius));
    }
  }
  return box;
}

View frame_object(const SceneObject& object, int width, int height, const FramingOptions& opt) {
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
  if (const auto* soup = std::get_if<PolygonSoup>(&object.geometry)) {
    centres = soup->points;
  } else {
    for (const auto& a : std::get<MedialSurface>(object.geometry).atoms) {
      centres.push_back(a.centre);
      radii.push_back(a.radius);
    }
  }
  try {
    return frame_view(centres, radii, width, height, opt);
  } catch (const InvalidInput& e) {
    throw InvalidInput(object.name + ": " + e.what());
  }
}

Eigen::Vector3d radius_colour(double t) {
  t = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0);
  // Hue 0 (red) .. 240 degrees (blue), in sextants of 60 degrees: HSV with S = V = 1.
  const double h = 4.0 * t;  // 0..4
  const int sextant = std::min(static_cast<int>(h), 3);
  const double f = h - sextant;
  switch (sextant) {
    case 0:
      return {1.0, f, 0.0};  // red -> yellow
    case 1:
      return {1.0 - f, 1.0, 0.0};  // yellow -> green
    case 2:
      return {0.0, 1.0, f};  // green -> cyan
    default:
      return {0.0, 1.0 - f, 1.0};  // cyan -> blue
  }
}

std::string povray_camera(const View& view) {
  validate(view, "view");
  Text out;
  out << "camera {\n  perspective\n  location ";
  out.vector(view.location) << "\n  right <" << -static_cast<double>(view.width) / view.height
                            << ", 0, 0>  // negative: right-handed model coordinates\n"
                            << "  up <0, 1, 0>\n  angle " << view.angle << "\n  sky ";
  out.vector(view.sky) << "\n  look_at ";
  out.vector(view.look_at) << "\n}\n";
  return out.take();
}

std::string povray_scene(const std::vector<SceneObject>& objects, const View& view,
                         const SceneOptions& opt) {
  if (objects.empty()) throw InvalidInput("povray_scene: no object to render");
  if (!(opt.mesh_transmit >= 0 && opt.mesh_transmit < 1))
    throw InvalidInput("mesh transmit must be in [0, 1), got " + std::to_string(opt.mesh_transmit));
  if (opt.colour_levels < 2) throw InvalidInput("colour levels must be >= 2");
  const Frame f = frame_of(view);
  const double reach = 2.0 * f.distance;
  auto light = [&](double right, double up, double back) {
    return Eigen::Vector3d(view.look_at +
                           reach * (right * f.right + up * f.up - back * f.forward).normalized());
  };

  Text out;
  out << "// POV-Ray 3.7 scene written by mg::render::povray_scene (medial surface garbing)\n"
      << "#version 3.7;\n"
      << "global_settings { assumed_gamma 1.0 max_trace_level " << (opt.mesh_transmit > 0 ? 12 : 5)
      << " }\n"
      << "background { rgb <1, 1, 1> }\n"
      << povray_camera(view)
      << "// key light (upper left, shadows), fill light (right), rim light (behind, above)\n"
      << "light_source { ";
  out.vector(light(-0.7, 0.9, 1.0)) << " rgb 0.85 }\nlight_source { ";
  out.vector(light(1.0, 0.2, 0.7)) << " rgb 0.35 shadowless }\nlight_source { ";
  out.vector(light(0.3, 1.0, -1.0)) << " rgb 0.3 shadowless }\n";
  out << "#declare mg_finish = finish { ambient 0.12 diffuse 0.75 specular 0.2 roughness 0.03 }\n";

  int meshes = 0, surfaces = 0;
  for (const SceneObject& object : objects) {
    if (const auto* soup = std::get_if<PolygonSoup>(&object.geometry))
      write_mesh(out, *soup, object.name, meshes++, opt);
    else
      write_medial_surface(out, std::get<MedialSurface>(object.geometry), object.name, surfaces++,
                           opt);
  }
  return out.take();
}

}  // namespace mg::render
