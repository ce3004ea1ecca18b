// The envelope of a medial mesh: which of its edges become cones and which faces slabs.
#include "core/errors.h"
#include "garbing/target_shape.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mg::garbing {

PrimitiveSet parse_primitive_set(const std::string& name) {
  if (name == "auto") return PrimitiveSet::automatic;
  if (name == "ma") return PrimitiveSet::envelope;
  if (name == "rt") return PrimitiveSet::atoms;
  throw InvalidInput("unknown primitive set '" + name + "' (expected auto, ma or rt)");
}

PrimitiveSet resolve(PrimitiveSet set, const MedialSurface& atoms) {
  if (set != PrimitiveSet::automatic) return set;
  return atoms.edges.empty() && atoms.faces.empty() ? PrimitiveSet::atoms : PrimitiveSet::envelope;
}

namespace {

/// Whether one ball holds the other, up to a relative 1e-12 (a cone needs L > |r1 - r2|
/// in the frame it is built in too).
bool one_holds_other(const MedialAtom& a, const MedialAtom& b) {
  const double L = (b.centre - a.centre).norm();
  return !(L > std::abs(a.radius - b.radius) + 1e-12 * (L + a.radius + b.radius));
}

}  // namespace

EnvelopePrimitives envelope_primitives(const MedialSurface& s) {
  validate(s);
  EnvelopePrimitives out;
  EnvelopeCounts& n = out.counts;
  // Every edge line and every side of every face, smaller index first.
  std::vector<std::array<int, 2>> edges;
  edges.reserve(s.edges.size() + 3 * s.faces.size());
  auto add_edge = [&](int i, int j) {
    if (i == j) return;  // validate() refuses them; a face repeating an atom too
    edges.push_back({std::min(i, j), std::max(i, j)});
  };
  for (const auto& e : s.edges) add_edge(e[0], e[1]);
  std::vector<std::array<int, 3>> faces;
  faces.reserve(s.faces.size());
  for (auto f : s.faces) {
    for (int k = 0; k < 3; ++k) add_edge(f[k], f[(k + 1) % 3]);
    std::sort(f.begin(), f.end());
    faces.push_back(f);
  }
  const long edge_lines = static_cast<long>(edges.size());
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  n.edges = static_cast<long>(edges.size());
  n.repeated_edges = edge_lines - n.edges;
  for (const auto& [i, j] : edges) {
    if (one_holds_other(s.atoms[i], s.atoms[j]))
      ++n.edges_in_a_ball;
    else
      out.cones.push_back({i, j});
  }
  const long face_lines = static_cast<long>(faces.size());
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  n.faces = static_cast<long>(faces.size());
  n.repeated_faces = face_lines - n.faces;
  for (const auto& f : faces) {
    if (collinear_centres(s.atoms[f[0]], s.atoms[f[1]], s.atoms[f[2]])) {
      ++n.collinear_faces;
      continue;
    }
    out.slabs.push_back(f);
  }
  return out;
}

TargetShape make_target_shape(MedialSurface atoms, PrimitiveSet primitives,
                              const ConeOptions& cones, const Frame& frame) {
  if (resolve(primitives, atoms) == PrimitiveSet::atoms)
    return make_target_shape(std::move(atoms), cones, frame);
  if (std::none_of(atoms.atoms.begin(), atoms.atoms.end(),
                   [](const MedialAtom& a) { return a.radius > 0; }))
    throw InvalidInput("every atom has radius 0: the envelope has no volume to garb");
  const EnvelopePrimitives e = envelope_primitives(atoms);
  return TargetShape(std::move(atoms), e.cones, e.slabs, frame, e.counts);
}

}  // namespace mg::garbing
