#include "render/povray_scene.h"

#include "core/errors.h"
#include "core/mesh_io.h"
#include "garbing/primitives.h"
#include "garbing/slab.h"

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

/// The colour level of every atom (its radius over the surface's radii, quantised to `levels`),
/// and the surface's smallest and largest radius.
struct RadiusLevels {
  std::vector<int> level;
  double lo = 0, hi = 0;
};

RadiusLevels radius_levels(const MedialSurface& s, int levels) {
  RadiusLevels r;
  r.lo = r.hi = s.atoms[0].radius;
  for (const auto& a : s.atoms) {
    r.lo = std::min(r.lo, a.radius);
    r.hi = std::max(r.hi, a.radius);
  }
  r.level.resize(s.atoms.size());
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    const double t = r.hi > r.lo ? (s.atoms[i].radius - r.lo) / (r.hi - r.lo) : 0.5;
    r.level[i] = static_cast<int>(std::lround(t * (levels - 1)));
  }
  return r;
}

/// radius_colour() is linear in RGB between these values of t (yellow, green, cyan) and its
/// ends (red, blue). A cone's or slab's surface point touches an interpolated ball whose radius
/// is linear in the point's position, so colours interpolated linearly between atoms' colours
/// and these breaks are radius_colour() of that radius exactly.
constexpr std::array<double, 3> kHueBreaks = {0.25, 0.5, 0.75};

/// The envelope's cones: the lateral surface of each (an open POV-Ray cone between its two
/// tangent circles; the caps would lie inside the balls). Its colour runs along the axis from
/// its first atom's level colour at one rim to its second's at the other, through the hue
/// breaks in between (one level: that level's texture). The gradient spans the middle half of
/// its period, [0.25, 0.75], so no point of the lateral surface wraps round to the other end.
void write_cones(Text& out, const MedialSurface& s, const std::vector<std::array<int, 2>>& pairs,
                 const std::vector<int>& level, const std::string& prefix, int levels) {
  std::vector<garbing::Cone> cones;
  cones.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    garbing::Cone k = garbing::make_cone(s.atoms[i], s.atoms[j], i, j);
    // A lateral surface of no width or no radius shows nothing (and POV-Ray refuses a cone of
    // zero length): the pair's hull is its balls.
    if (!(k.t_hi - k.t_lo > 1e-9 * (k.length + k.r1 + k.r2)) || !(k.rho_lo > 0 || k.rho_hi > 0))
      continue;
    cones.push_back(std::move(k));
  }
  std::vector<bool> gradient_end(levels, false);
  for (const auto& k : cones)
    if (level[k.a] != level[k.b]) gradient_end[level[k.a]] = gradient_end[level[k.b]] = true;
  out << "// cones: " << cones.size()
      << ", lateral surfaces between tangent circles, coloured along the axis by radius\n";
  for (int l = 0; l < levels; ++l) {
    if (!gradient_end[l]) continue;
    out << "#declare " << prefix << "rgb" << l << " = rgb ";
    out.rounded_vector(radius_colour(static_cast<double>(l) / (levels - 1)), 6) << ";\n";
  }
  for (const auto& k : cones) {
    const Eigen::Vector3d base = k.c1 + k.t_lo * k.u, cap = k.c1 + k.t_hi * k.u;
    out << "cone { ";
    out.vector(base) << ", " << k.rho_lo << ", ";
    out.vector(cap) << ", " << k.rho_hi << " open texture { ";
    const int la = level[k.a], lb = level[k.b];
    if (la == lb) {
      out << prefix << la << " } }\n";
      continue;
    }
    // The rim at t_lo touches ball a, the one at t_hi ball b; between them the touching ball's
    // radius, hence its colour value, is linear in the axial position.
    const double va = static_cast<double>(la) / (levels - 1);
    const double vb = static_cast<double>(lb) / (levels - 1);
    const double span = k.t_hi - k.t_lo;
    out << "pigment { gradient ";
    out.rounded_vector(k.u, 9) << " color_map { [0.25 " << prefix << "rgb" << la << "] ";
    for (int x = 0; x < 3; ++x) {
      const int b = va < vb ? x : 2 - x;  // increasing along the axis
      const double f = (kHueBreaks[b] - va) / (vb - va);
      if (!(f > 0 && f < 1)) continue;
      out << '[';
      out.rounded(0.25 + 0.5 * f, 9) << " rgb ";
      out.rounded_vector(radius_colour(kHueBreaks[b]), 6) << "] ";
    }
    out << "[0.75 " << prefix << "rgb" << lb << "] } scale " << 2 * span << " translate ";
    out.vector(base - (span / 2) * k.u) << " } finish { mg_finish } } }\n";
  }
}

/// A point of a slab's tangent triangle: its position, colour value t in [0, 1]
/// (radius_colour(t)) and colour key (a level < levels, or levels + b for hue break b).
struct ColouredPoint {
  Eigen::Vector3d p;
  double t;
  int key;
};

/// Appends to `mesh` the triangles of tangent triangle `tri` cut along the hue breaks its colour
/// values cross (t is linear over the triangle): its boundary points (the corners and, edge by
/// edge, where t crosses a break) are appended to `points` once; each band of t between breaks
/// is the convex polygon of the boundary points in it, in order round the boundary, fanned into
/// triangles (those of zero area left out). Neighbouring pieces share their cut points exactly.
void split_at_hue_breaks(const std::array<ColouredPoint, 3>& tri, int levels,
                         std::vector<ColouredPoint>& points,
                         std::vector<std::array<int, 3>>& mesh) {
  const int first = static_cast<int>(points.size());
  for (int e = 0; e < 3; ++e) {
    const ColouredPoint &p = tri[e], &q = tri[(e + 1) % 3];
    points.push_back(p);
    for (int x = 0; x < 3; ++x) {
      const int b = p.t < q.t ? x : 2 - x;  // from p to q
      const double tb = kHueBreaks[b];
      if (!(std::min(p.t, q.t) < tb && tb < std::max(p.t, q.t))) continue;
      const double f = (tb - p.t) / (q.t - p.t);
      points.push_back({p.p + f * (q.p - p.p), tb, levels + b});
    }
  }
  const int end = static_cast<int>(points.size());
  auto fan = [&](const std::vector<int>& polygon) {
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      const Eigen::Vector3d& a = points[polygon[0]].p;
      if ((points[polygon[i]].p - a).cross(points[polygon[i + 1]].p - a).squaredNorm() > 0)
        mesh.push_back({polygon[0], polygon[i], polygon[i + 1]});
    }
  };
  const double lo = std::min({tri[0].t, tri[1].t, tri[2].t});
  const double hi = std::max({tri[0].t, tri[1].t, tri[2].t});
  std::vector<double> bounds = {-1};  // the bands' limits: the breaks crossed, between -1 and 2
  for (double tb : kHueBreaks)
    if (lo < tb && tb < hi) bounds.push_back(tb);
  bounds.push_back(2);
  std::vector<int> polygon;
  for (std::size_t band = 0; band + 1 < bounds.size(); ++band) {
    polygon.clear();
    for (int i = first; i < end; ++i)
      if (points[i].t >= bounds[band] && points[i].t <= bounds[band + 1]) polygon.push_back(i);
    fan(polygon);
  }
}

/// The envelope's slabs: the two tangent triangles of each slab that has them, all in one mesh2
/// (POV-Ray bounds its triangles with a tree of their own), flat (the triangles are planar
/// faces of the envelope). Each corner takes its atom's level texture and POV-Ray interpolates
/// the three colours across the triangle; a triangle whose colours cross a hue break is cut
/// along it first, so the colour at every point is radius_colour() of the radius of the ball
/// touching it there, as on the cones. A slab without tangent triangles adds nothing to its
/// balls and edge cones.
void write_slabs(Text& out, const MedialSurface& s, const std::vector<std::array<int, 3>>& triples,
                 const std::vector<int>& level, const std::string& prefix, int levels) {
  std::vector<ColouredPoint> points;
  std::vector<std::array<int, 3>> mesh;
  points.reserve(6 * triples.size());
  mesh.reserve(2 * triples.size());
  std::size_t slabs = 0;
  for (const auto& f : triples) {
    const garbing::Slab slab =
        garbing::make_slab(s.atoms[f[0]], s.atoms[f[1]], s.atoms[f[2]], f[0], f[1], f[2]);
    if (!slab.has_tangent_triangles) continue;
    ++slabs;
    for (const auto& t : slab.tangent) {
      std::array<ColouredPoint, 3> tri;
      for (int x = 0; x < 3; ++x)
        tri[x] = {t[x], static_cast<double>(level[f[x]]) / (levels - 1), level[f[x]]};
      split_at_hue_breaks(tri, levels, points, mesh);
    }
  }
  out << "// slabs: " << slabs << " with tangent triangles (" << triples.size() - slabs
      << " without): " << mesh.size() << " triangles, coloured by radius\n";
  if (mesh.empty()) return;
  // The texture list: the colour keys used, in increasing order.
  std::vector<bool> in_list(levels + kHueBreaks.size(), false);
  for (const auto& c : points) in_list[c.key] = true;
  std::vector<int> list_index(in_list.size(), -1);
  int list_size = 0;
  for (std::size_t key = 0; key < in_list.size(); ++key)
    if (in_list[key]) list_index[key] = list_size++;
  out << "mesh2 {\n  vertex_vectors { " << points.size();
  for (const auto& c : points) {
    out << ",\n    ";
    out.vector(c.p);
  }
  out << "}\n  texture_list { " << list_size;
  for (std::size_t key = 0; key < in_list.size(); ++key) {
    if (!in_list[key]) continue;
    if (key < static_cast<std::size_t>(levels)) {
      out << ",\n    texture { " << prefix << key << " }";
    } else {
      out << ",\n    texture { pigment { rgb ";
      out.rounded_vector(radius_colour(kHueBreaks[key - levels]), 6) << " } finish { mg_finish } }";
    }
  }
  out << "}\n  face_indices { " << mesh.size();
  for (const auto& t : mesh)
    out << ",\n    <" << t[0] << ", " << t[1] << ", " << t[2] << ">, "
        << list_index[points[t[0]].key] << ", " << list_index[points[t[1]].key] << ", "
        << list_index[points[t[2]].key];
  out << "}\n}\n";
}

void write_medial_surface(Text& out, const MedialSurface& s, const std::string& name, int rank,
                          const SceneOptions& opt) {
  try {
    validate(s);
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
  const bool envelope = garbing::resolve(opt.primitives, s) == garbing::PrimitiveSet::envelope;
  garbing::EnvelopePrimitives hulls;
  if (envelope) hulls = garbing::envelope_primitives(s);
  const int levels = opt.colour_levels;
  const RadiusLevels r = radius_levels(s, levels);
  const std::string prefix = "mg_atoms" + std::to_string(rank) + "_";
  out << "// medial surface " << rank << ": " << name << " (" << s.atoms.size();
  out << " atoms as spheres";
  if (envelope)
    out << " and the envelope of its " << static_cast<long long>(hulls.counts.edges)
        << " edges and " << static_cast<long long>(hulls.counts.faces) << " faces";
  out << "; radius " << r.lo << " (red) to " << r.hi << " (blue), " << levels
      << " colour levels)\n";
  std::vector<bool> used(levels, false);
  for (int l : r.level) used[l] = true;
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
                                  << r.level[i] << " } }\n";
  }
  if (!envelope) return;
  write_cones(out, s, hulls.cones, r.level, prefix, levels);
  write_slabs(out, s, hulls.slabs, r.level, prefix, levels);
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
