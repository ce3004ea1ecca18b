// The Python module `garbing`: the libraries' entry points on NumPy arrays (python/README in
// the top README, "Python"). A front end like the programs: it converts and checks arrays,
// calls the same library functions with the same options, and maps the exception family to
// Python's (InvalidInput -> ValueError, IoError -> OSError, the rest -> RuntimeError) with the
// same one-line messages. The GIL is released while the libraries work.
#include "core/errors.h"
#include "core/medial_surface.h"
#include "core/mesh.h"
#include "evaluate/mesh_checks.h"
#include "evaluate/mesh_distance.h"
#include "garbing/garb.h"
#include "skeletonize/poles.h"
#include "skeletonize/simplify.h"
#include "skeletonize/union_topology.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace py = pybind11;
using Eigen::Vector3d;

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Ints = py::array_t<long long, py::array::c_style | py::array::forcecast>;

[[noreturn]] void bad(const std::string& what) { throw mg::InvalidInput(what); }

/// An (n, 3) float array as points; `name` in messages.
std::vector<Vector3d> points_of(const Doubles& a, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    bad(std::string(name) + ": expected an array of shape (n, 3), got " + std::to_string(a.ndim()) +
        " dimension(s)" +
        (a.ndim() == 2 ? " with " + std::to_string(a.shape(1)) + " columns" : ""));
  const auto v = a.unchecked<2>();
  std::vector<Vector3d> out(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    out[i] = Vector3d(v(i, 0), v(i, 1), v(i, 2));
    if (!out[i].allFinite())
      bad(std::string(name) + ": row " + std::to_string(i) + " is not finite");
  }
  return out;
}

/// An (m, K) integer array (any integer dtype) as index tuples in [0, n); an empty array of
/// shape (0,) or (0, K) is none. `name` in messages.
template <std::size_t K>
std::vector<std::array<int, K>> indices_of(const py::array& raw, std::size_t n, const char* name) {
  const char kind = raw.dtype().kind();
  if (kind != 'i' && kind != 'u')
    bad(std::string(name) + ": expected an integer array, got dtype " +
        std::string(py::str(raw.dtype())));
  if (raw.ndim() == 1 && raw.shape(0) == 0) return {};
  if (raw.ndim() != 2 || raw.shape(1) != static_cast<py::ssize_t>(K))
    bad(std::string(name) + ": expected an integer array of shape (m, " + std::to_string(K) + ")");
  const Ints a = Ints::ensure(raw);
  const auto v = a.unchecked<2>();
  std::vector<std::array<int, K>> out(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (std::size_t k = 0; k < K; ++k) {
      const long long x = v(i, static_cast<py::ssize_t>(k));
      if (x < 0 || x >= static_cast<long long>(n))
        bad(std::string(name) + ": row " + std::to_string(i) + " has index " + std::to_string(x) +
            ", out of range (" + std::to_string(n) + ")");
      out[i][k] = static_cast<int>(x);
    }
  return out;
}

/// A triangle mesh (V, F) as a polygon soup, checked as every reader checks files.
mg::PolygonSoup soup_of(const Doubles& vertices, const py::array& faces, const char* name) {
  mg::PolygonSoup soup;
  soup.points = points_of(vertices, (std::string(name) + " vertices").c_str());
  for (const auto& f :
       indices_of<3>(faces, soup.points.size(), (std::string(name) + " faces").c_str()))
    soup.faces.push_back({f[0], f[1], f[2]});
  if (soup.faces.empty()) bad(std::string(name) + ": no faces");
  mg::validate_soup(soup, name);
  return soup;
}

/// Atoms from centres (n, 3), radii (n,) and optional edges (m, 2) and faces (k, 3).
mg::MedialSurface atoms_of(const Doubles& centres, const Doubles& radii,
                           const std::optional<py::array>& edges,
                           const std::optional<py::array>& faces) {
  const std::vector<Vector3d> c = points_of(centres, "centres");
  if (radii.ndim() != 1 || radii.shape(0) != static_cast<py::ssize_t>(c.size()))
    bad("radii: expected an array of shape (" + std::to_string(c.size()) + ",), one per centre");
  mg::MedialSurface s;
  const auto r = radii.unchecked<1>();
  for (std::size_t i = 0; i < c.size(); ++i) s.atoms.push_back({c[i], r(i)});
  if (edges) s.edges = indices_of<2>(*edges, c.size(), "edges");
  if (faces) s.faces = indices_of<3>(*faces, c.size(), "faces");
  mg::validate(s);  // radii finite and >= 0, no edge to itself, ... (the .ma reader's rules)
  return s;
}

py::array_t<double> points_array(const std::vector<Vector3d>& p) {
  py::array_t<double> a({static_cast<py::ssize_t>(p.size()), py::ssize_t(3)});
  auto v = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k) v(i, k) = p[i][k];
  return a;
}

template <class Rows>
py::array_t<std::int32_t> index_array(const Rows& rows, std::size_t k) {
  py::array_t<std::int32_t> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(k)});
  auto v = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < k; ++j) v(i, j) = static_cast<std::int32_t>(rows[i][j]);
  return a;
}

py::tuple atoms_tuple(const mg::MedialSurface& s) {
  std::vector<Vector3d> c;
  py::array_t<double> r(static_cast<py::ssize_t>(s.atoms.size()));
  auto rv = r.mutable_unchecked<1>();
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    c.push_back(s.atoms[i].centre);
    rv(i) = s.atoms[i].radius;
  }
  return py::make_tuple(points_array(c), r, index_array(s.edges, 2), index_array(s.faces, 3));
}

/// A thread limit for the call (0: every core), as the programs' --threads.
std::unique_ptr<tbb::global_control> limit(int threads) {
  if (threads < 0) bad("threads must be >= 0, got " + std::to_string(threads));
  if (threads == 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(threads));
}

py::tuple skeletonize(const Doubles& vertices, const py::array& faces,
                      const py::object& samples_arg, std::uint64_t seed, double merge_tol,
                      bool clamp_radius, double drop_isolated, bool connectivity,
                      std::size_t simplify, int threads) {
  mg::skeletonize::SkeletonOptions opt;
  // samples: 'vertices', 'midpoints' or a count (an int, or its digits), as --samples.
  if (!py::isinstance<py::int_>(samples_arg) && !py::isinstance<py::str>(samples_arg))
    bad("samples: expected vertices, midpoints or a count, got " +
        std::string(py::str(py::repr(samples_arg))));
  const std::string samples = std::string(py::str(samples_arg));
  if (samples == "midpoints") {
    opt.edge_midpoints = true;
  } else if (samples != "vertices") {
    const bool digits = !samples.empty() && samples.size() <= 12 &&
                        samples.find_first_not_of("0123456789") == std::string::npos;
    if (!digits) bad("samples: expected vertices, midpoints or a count, got '" + samples + "'");
    opt.random_samples = std::stoul(samples);
  }
  opt.seed = seed;
  opt.merge_tol = merge_tol;
  opt.clamp_radius = clamp_radius;
  opt.isolated_fraction = drop_isolated;
  opt.connectivity = connectivity || simplify > 0;
  const mg::PolygonSoup mesh = soup_of(vertices, faces, "mesh");
  mg::MedialSurface out;
  {
    py::gil_scoped_release release;
    const auto limited = limit(threads);
    const mg::skeletonize::Skeleton s = mg::skeletonize::skeletonize(mesh, opt, "mesh");
    if (simplify > 0) {
      if (simplify > s.atoms.atoms.size())
        bad("simplify: " + std::to_string(simplify) + " is more than the skeleton's " +
            std::to_string(s.atoms.atoms.size()) + " atoms");
      mg::skeletonize::SimplifyOptions sopt;
      sopt.target_atoms = simplify;
      out = mg::skeletonize::simplify_medial_mesh(mesh, s.atoms, s.cells, sopt, s.samples,
                                                  s.atom_of_sample, &*s.union_complex)
                .surface;
    } else {
      out = s.atoms;
    }
  }
  const py::tuple all = atoms_tuple(out);
  if (opt.connectivity) return all;
  return py::make_tuple(all[0], all[1]);
}

py::tuple garb(const Doubles& centres, const Doubles& radii, const std::optional<py::array>& edges,
               const std::optional<py::array>& faces, int min_depth, int max_depth,
               const std::string& primitives, const std::optional<std::string>& cones,
               const std::optional<double>& cone_filter, const std::optional<double>& cone_collar,
               bool spheres_only, int refine, bool dual, double max_travel, int repair_rounds,
               double max_gap, double tolerance, const std::optional<std::string>& thinning_given,
               int threads) {
  namespace gb = mg::garbing;
  const mg::MedialSurface atoms = atoms_of(centres, radii, edges, faces);
  gb::GarbOptions opt;
  if (min_depth < 0) bad("min_depth must be >= 0, got " + std::to_string(min_depth));
  if (max_depth < 1 || max_depth > 20)
    bad("max_depth must be in [1, 20], got " + std::to_string(max_depth));
  if (cone_filter && !(*cone_filter >= 0 && *cone_filter <= 1))
    bad("cone_filter must be in [0, 1], got " + std::to_string(*cone_filter));
  if (cone_collar && !(*cone_collar >= 0))
    bad("cone_collar must be >= 0, got " + std::to_string(*cone_collar));
  opt.octree.min_depth = min_depth;
  opt.octree.max_depth = max_depth;
  opt.primitives = gb::parse_primitive_set(primitives);
  opt.cones.source =
      spheres_only ? gb::ConeSource::none : gb::parse_cone_source(cones.value_or("rt"));
  if (cone_filter) opt.cones.min_circle_ratio = *cone_filter;
  if (cone_collar) opt.cones.max_collar = *cone_collar;
  // As `garb`: any cone option means the atoms' balls and cones, not an envelope.
  if (cones || cone_filter || cone_collar || spheres_only) {
    if (opt.primitives == gb::PrimitiveSet::envelope)
      bad("cones, cone_filter, cone_collar and spheres_only choose the cones of "
          "primitives='rt', not 'ma'");
    opt.primitives = gb::PrimitiveSet::atoms;
  }
  opt.refine.subdivisions = refine;
  opt.refine.dual = dual;
  opt.refine.max_travel = max_travel;
  opt.refine.repair_rounds = repair_rounds;
  opt.refine.max_gap = max_gap;
  opt.tolerance = tolerance;  // garb() checks it
  const std::string thinning = thinning_given.value_or("cover");
  if (thinning != "cover" && thinning != "contain")
    bad("thinning must be 'cover' or 'contain', got '" + thinning + "'");
  if (thinning_given && !(tolerance > 0))  // as `garb --thinning`
    bad("thinning chooses how tolerance thins: give tolerance > 0");
  opt.thinning = thinning == "contain" ? gb::ThinMethod::contain : gb::ThinMethod::cover;
  if (gb::resolve(opt.primitives, atoms) == gb::PrimitiveSet::atoms)
    for (std::size_t i = 0; i < atoms.atoms.size(); ++i)
      if (!(atoms.atoms[i].radius > 0))
        bad("atom " + std::to_string(i) +
            " has radius 0: the balls alone (primitives='rt') need radii > 0");
  std::optional<gb::Garbing> r;
  mg::PolygonSoup m2;
  {
    py::gil_scoped_release release;
    const auto limited = limit(threads);
    r.emplace(gb::garb(atoms, opt));
    m2 = mg::soup_from_mesh(r->m2.mesh);
  }
  const gb::RefineStats& s = r->m2.stats;
  py::dict stats;
  stats["atoms"] = atoms.atoms.size();
  stats["primitives"] =
      gb::resolve(opt.primitives, atoms) == gb::PrimitiveSet::envelope ? "ma" : "rt";
  stats["min_depth"] = r->tree.min_depth;
  stats["depth"] = r->tree.depth;
  stats["hit_max_depth"] = r->tree.hit_max_depth;
  stats["depth_stopped_cells"] = r->tree.depth_stopped;
  stats["leaves"] = r->tree.leaves.size();
  stats["m1_faces"] = r->m1.mesh.n_faces();
  stats["cones"] = r->g.cone_count();
  stats["slabs"] = r->g.slab_count();
  stats["intersecting_pairs_after_repair"] = s.intersecting_after;
  stats["degenerate_after_repair"] = s.degenerate_after;
  if (tolerance > 0)
    stats["thinning"] = py::dict(
        py::arg("tolerance_leaf_sides") = tolerance, py::arg("method") = thinning,
        py::arg("slack") = r->thinning.slack, py::arg("atoms_kept") = r->thinning.kept,
        py::arg("atoms_dropped") = r->thinning.dropped,
        py::arg("atoms_covered") = r->thinning.covered, py::arg("seconds") = r->thinning.seconds);
  stats["seconds"] =
      py::dict(py::arg("cones") = r->seconds.target_shape, py::arg("octree") = r->seconds.octree,
               py::arg("m1") = r->seconds.m1, py::arg("m2") = r->seconds.m2,
               py::arg("garbing") = r->seconds.total());
  std::vector<std::array<int, 3>> tris;
  for (const auto& f : m2.faces) tris.push_back({f[0], f[1], f[2]});
  return py::make_tuple(points_array(m2.points), index_array(tris, 3), stats);
}

py::dict one_sided(const mg::evaluate::OneSidedDistance& d, double diagonal) {
  return py::dict(py::arg("max") = d.max,
                  py::arg("max_pct") = mg::evaluate::percent_of_diagonal(d.max, diagonal),
                  py::arg("mean") = d.mean, py::arg("rms") = d.rms, py::arg("samples") = d.samples);
}

py::dict distance(const Doubles& va, const py::array& fa, const Doubles& vb, const py::array& fb,
                  std::size_t samples, std::uint64_t seed, bool faces_only, int threads) {
  const mg::PolygonSoup a = soup_of(va, fa, "mesh"), b = soup_of(vb, fb, "reference");
  mg::evaluate::MeshDistanceOptions opt;
  opt.samples = samples;
  opt.seed = seed;
  opt.vertices_and_edges = !faces_only;
  mg::evaluate::MeshDistance d;
  {
    py::gil_scoped_release release;
    const auto limited = limit(threads);
    d = mg::evaluate::mesh_distance(a, b, opt, "mesh", "reference");
  }
  const double diag = d.diagonal;
  using mg::evaluate::percent_of_diagonal;
  return py::dict(py::arg("diagonal") = diag, py::arg("hausdorff") = d.distance.hausdorff,
                  py::arg("hausdorff_pct") = percent_of_diagonal(d.distance.hausdorff, diag),
                  py::arg("rms") = d.distance.rms,
                  py::arg("rms_pct") = percent_of_diagonal(d.distance.rms, diag),
                  py::arg("mean") = d.distance.mean,
                  py::arg("mean_pct") = percent_of_diagonal(d.distance.mean, diag),
                  py::arg("samples") = d.samples,
                  py::arg("mesh_to_reference") = one_sided(d.distance.a_to_b, diag),
                  py::arg("reference_to_mesh") = one_sided(d.distance.b_to_a, diag));
}

py::dict check(const Doubles& vertices, const py::array& faces, int threads) {
  const mg::PolygonSoup soup = soup_of(vertices, faces, "mesh");
  mg::evaluate::MeshCheck c;
  {
    py::gil_scoped_release release;
    const auto limited = limit(threads);
    c = mg::evaluate::check_mesh(soup);
  }
  const mg::MeshTopology& t = c.topology;
  return py::dict(py::arg("vertices") = soup.points.size(), py::arg("faces") = soup.faces.size(),
                  py::arg("closed") = t.closed, py::arg("manifold") = t.manifold,
                  py::arg("oriented") = t.oriented, py::arg("components") = t.components,
                  py::arg("euler") = t.euler, py::arg("genus") = t.genus,
                  py::arg("intersecting_pairs") = c.intersecting_pairs,
                  py::arg("degenerate_triangles") = c.degenerate_triangles,
                  py::arg("min_angle_deg") = c.min_angle_deg);
}

}  // namespace

PYBIND11_MODULE(garbing, m) {
  m.doc() =
      "Medial surface garbing: medial atoms of a closed mesh, the closed mesh of atoms or of a "
      "medial mesh's envelope, and Metro-style distances. Arrays: float64 points (n, 3), "
      "integer indices; the options are the programs' (skeletonize, garb, evaluate).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const mg::InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const mg::IoError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const mg::Error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });
  m.def("skeletonize", &skeletonize, py::arg("vertices"), py::arg("faces"), py::kw_only(),
        py::arg("samples") = "vertices", py::arg("seed") = 1, py::arg("merge_tol") = -1.0,
        py::arg("clamp_radius") = false, py::arg("drop_isolated") = 1e-2,
        py::arg("connectivity") = false, py::arg("simplify") = 0, py::arg("threads") = 0,
        R"(Inner Voronoi poles of a closed triangle mesh, as `skeletonize`.

vertices (n, 3) float64, faces (m, 3) integers: a closed, oriented 2-manifold.
samples: 'vertices', 'midpoints' or a count of random face points (as a string or int).
merge_tol: poles closer than T/2 are one atom (negative: 1e-3 of the diagonal).
clamp_radius: radius = distance from the centre to the mesh. connectivity: also the regular
triangulation's edges and triangles inside the object. simplify: collapse the poles' medial
mesh to this many atoms (implies connectivity). threads: 0 = every core.
Returns (centres (k, 3), radii (k,)) or, with connectivity or simplify,
(centres, radii, edges (e, 2) int32, faces (f, 3) int32). Raises ValueError on bad input.)");
  m.def("garb", &garb, py::arg("centres"), py::arg("radii"), py::arg("edges") = py::none(),
        py::arg("faces") = py::none(), py::kw_only(), py::arg("min_depth") = 0,
        py::arg("max_depth") = 14, py::arg("primitives") = "auto", py::arg("cones") = py::none(),
        py::arg("cone_filter") = py::none(), py::arg("cone_collar") = py::none(),
        py::arg("spheres_only") = false, py::arg("refine") = 0, py::arg("dual") = true,
        py::arg("max_travel") = 4.0, py::arg("repair_rounds") = 8, py::arg("max_gap") = 0.5,
        py::arg("tolerance") = 0.0, py::arg("thinning") = py::none(), py::arg("threads") = 0,
        R"(The garbing of medial atoms, as `garb`: a closed triangle mesh M2.

centres (n, 3) float64, radii (n,); edges (e, 2) and faces (f, 3) make a medial mesh whose
envelope (balls, cones, slabs) is garbed (primitives='auto' or 'ma'); 'rt' garbs the balls and
the cones of `cones` ('rt', 'all', 'edges', 'none'). cone_filter and cone_collar (garb's defaults 0.9 and 1), like cones, mean primitives='rt'.
tolerance: thin dense atoms first (leaf sides at depth d; stats['thinning'] says how many
were kept), by thinning='cover' (the default: nearby kept balls together cover a ball that
goes) or 'contain' (one kept ball contains it); thinning without tolerance is refused. The other options are garb's.
Returns (vertices (v, 3) float64, faces (t, 3) int32, stats dict). Raises ValueError on bad input.)");
  m.def("distance", &distance, py::arg("mesh_vertices"), py::arg("mesh_faces"),
        py::arg("reference_vertices"), py::arg("reference_faces"), py::kw_only(),
        py::arg("samples") = 0, py::arg("seed") = 1, py::arg("faces_only") = false,
        py::arg("threads") = 0,
        R"(Two-sided Hausdorff, RMS and mean distance between two triangle meshes, as
`evaluate distance` (percentages of the reference's bounding-box diagonal).
Returns a dict: diagonal, hausdorff(_pct), rms(_pct), mean(_pct), samples, and both one-sided
distances.)");
  m.def("check", &check, py::arg("vertices"), py::arg("faces"), py::kw_only(),
        py::arg("threads") = 0,
        R"(Validity of a triangle mesh, as `evaluate check`: closed, manifold, oriented,
components, euler, genus, intersecting triangle pairs, degenerate triangles, minimum angle.)");
  m.def(
      "read_ma",
      [](const std::string& path) {
        mg::MedialSurface s;
        {
          py::gil_scoped_release release;
          s = mg::read_medial_surface(path);
        }
        return atoms_tuple(s);
      },
      py::arg("path"),
      "Reads a .ma file: (centres (n, 3), radii (n,), edges (e, 2) int32, faces (f, 3) int32).");
  m.def(
      "write_ma",
      [](const std::string& path, const Doubles& centres, const Doubles& radii,
         const std::optional<py::array>& edges, const std::optional<py::array>& faces) {
        const mg::MedialSurface s = atoms_of(centres, radii, edges, faces);
        py::gil_scoped_release release;
        mg::write_medial_surface(s, path);
      },
      py::arg("path"), py::arg("centres"), py::arg("radii"), py::arg("edges") = py::none(),
      py::arg("faces") = py::none(),
      "Writes a .ma file (through a temporary file renamed at the end).");
}
