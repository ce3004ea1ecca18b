// The simplicial complex of the simplification: stars as sorted lists, edge collapses under the
// link condition, elementary collapses.
#include "medial_complex.h"

#include "core/union_find.h"

#include <algorithm>
#include <iterator>

namespace mg::skeletonize::detail {
namespace {

template <class T>
void sort_unique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

template <class T>
void erase_sorted(std::vector<T>& v, const T& x) {
  const auto it = std::lower_bound(v.begin(), v.end(), x);
  if (it != v.end() && *it == x) v.erase(it);
}

template <class T>
bool contains_sorted(const std::vector<T>& v, const T& x) {
  return std::binary_search(v.begin(), v.end(), x);
}

/// Size of the intersection of two sorted lists.
template <class T>
long common_count(const std::vector<T>& a, const std::vector<T>& b) {
  long n = 0;
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i < *j)
      ++i;
    else if (*j < *i)
      ++j;
    else {
      ++n;
      ++i;
      ++j;
    }
  }
  return n;
}

template <std::size_t N>
bool has_vertex(const std::array<int, N>& s, int v) {
  return std::find(s.begin(), s.end(), v) != s.end();
}

/// s with `from` replaced by `to`, sorted.
template <std::size_t N>
std::array<int, N> replaced(std::array<int, N> s, int from, int to) {
  for (int& x : s)
    if (x == from) x = to;
  std::sort(s.begin(), s.end());
  return s;
}

/// In a list of opposite simplices of one vertex: those holding `gone` take `keep`, those holding
/// both are dropped (the simplex degenerates onto a face it already has), duplicates merge.
template <std::size_t N>
void relabel(std::vector<std::array<int, N>>& list, int keep, int gone) {
  bool changed = false;
  std::vector<std::array<int, N>> out;
  out.reserve(list.size());
  for (const auto& s : list) {
    if (!has_vertex(s, gone)) {
      out.push_back(s);
      continue;
    }
    changed = true;
    if (!has_vertex(s, keep)) out.push_back(replaced(s, gone, keep));
  }
  if (!changed) return;
  sort_unique(out);
  list = std::move(out);
}

}  // namespace

MedialComplex::MedialComplex(int vertices, const std::vector<Pair>& edges,
                             const std::vector<Triple>& triangles,
                             const std::vector<Quad>& tetrahedra)
    : neighbours_(vertices),
      triangle_links_(vertices),
      tetrahedron_links_(vertices),
      alive_(vertices, 1),
      vertices_(vertices),
      edges_(static_cast<long>(edges.size())),
      triangles_(static_cast<long>(triangles.size())),
      tetrahedra_(static_cast<long>(tetrahedra.size())) {
  for (const auto& e : edges) {
    neighbours_[e[0]].push_back(e[1]);
    neighbours_[e[1]].push_back(e[0]);
  }
  for (const auto& t : triangles) {
    triangle_links_[t[0]].push_back({t[1], t[2]});
    triangle_links_[t[1]].push_back({t[0], t[2]});
    triangle_links_[t[2]].push_back({t[0], t[1]});
  }
  for (const auto& t : tetrahedra)
    for (int k = 0; k < 4; ++k) {
      Triple o;
      for (int i = 0, j = 0; i < 4; ++i)
        if (i != k) o[j++] = t[i];
      tetrahedron_links_[t[k]].push_back(o);
    }
  for (int v = 0; v < vertices; ++v) {
    std::sort(neighbours_[v].begin(), neighbours_[v].end());
    std::sort(triangle_links_[v].begin(), triangle_links_[v].end());
    std::sort(tetrahedron_links_[v].begin(), tetrahedron_links_[v].end());
  }
}

long MedialComplex::components() const {
  UnionFind sets(neighbours_.size());
  for (std::size_t v = 0; v < neighbours_.size(); ++v)
    for (int u : neighbours_[v]) sets.unite(v, static_cast<std::size_t>(u));
  long n = 0;
  for (std::size_t v = 0; v < neighbours_.size(); ++v)
    if (alive_[v] && sets.find(v) == v) ++n;
  return n;
}

bool MedialComplex::has_edge(int u, int v) const { return contains_sorted(neighbours_[u], v); }

bool MedialComplex::has_triangle(const Triple& t) const {
  return contains_sorted(triangle_links_[t[0]], Pair{t[1], t[2]});
}

bool MedialComplex::has_tetrahedron(const Quad& t) const {
  return contains_sorted(tetrahedron_links_[t[0]], Triple{t[1], t[2], t[3]});
}

int MedialComplex::triangles_on_edge(int u, int v) const {
  int n = 0;
  for (const auto& p : triangle_links_[u]) n += has_vertex(p, v);
  return n;
}

int MedialComplex::tetrahedra_on_triangle(const Triple& t) const {
  int n = 0;
  for (const auto& q : tetrahedron_links_[t[0]]) n += has_vertex(q, t[1]) && has_vertex(q, t[2]);
  return n;
}

std::vector<std::vector<int>> MedialComplex::free_link_components(int a, int b) const {
  // I's vertices: the common neighbours; Lk(ab)'s: the c of the triangles abc (all common).
  std::vector<int> vertices;
  std::set_intersection(neighbours_[a].begin(), neighbours_[a].end(), neighbours_[b].begin(),
                        neighbours_[b].end(), std::back_inserter(vertices));
  if (static_cast<int>(vertices.size()) == triangles_on_edge(a, b)) return {};  // I = Lk(ab)'s
  // I's edges: the cd with triangles acd and bcd. (The lists of a hold no a, those of b no b,
  // so the common elements hold neither.)
  std::vector<Pair> edges;
  std::set_intersection(triangle_links_[a].begin(), triangle_links_[a].end(),
                        triangle_links_[b].begin(), triangle_links_[b].end(),
                        std::back_inserter(edges));
  auto local = [&](int v) {
    return static_cast<std::size_t>(std::lower_bound(vertices.begin(), vertices.end(), v) -
                                    vertices.begin());
  };
  UnionFind sets(vertices.size());
  for (const auto& e : edges) sets.unite(local(e[0]), local(e[1]));
  std::vector<char> anchored(vertices.size(), 0);
  for (const auto& p : triangle_links_[a])
    if (p[0] == b || p[1] == b) anchored[sets.find(local(p[0] == b ? p[1] : p[0]))] = 1;
  std::vector<std::vector<int>> free;
  std::vector<int> slot(vertices.size(), -1);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const std::size_t root = sets.find(i);
    if (anchored[root]) continue;
    if (slot[root] < 0) {
      slot[root] = static_cast<int>(free.size());
      free.emplace_back();
    }
    free[slot[root]].push_back(vertices[i]);
  }
  return free;
}

void MedialComplex::collapse(int keep, int gone) {
  const long star_edges =
      static_cast<long>(neighbours_[keep].size() + neighbours_[gone].size()) - 1;
  const long star_triangles =
      static_cast<long>(triangle_links_[keep].size() + triangle_links_[gone].size()) -
      triangles_on_edge(keep, gone);
  long tetrahedra_ab = 0;
  for (const auto& q : tetrahedron_links_[keep]) tetrahedra_ab += has_vertex(q, gone);
  const long star_tetrahedra =
      static_cast<long>(tetrahedron_links_[keep].size() + tetrahedron_links_[gone].size()) -
      tetrahedra_ab;

  // The other vertices of gone's star.
  for (int u : neighbours_[gone]) {
    if (u == keep) continue;
    auto& n = neighbours_[u];
    erase_sorted(n, gone);
    const auto it = std::lower_bound(n.begin(), n.end(), keep);
    if (it == n.end() || *it != keep) n.insert(it, keep);
    relabel(triangle_links_[u], keep, gone);
    relabel(tetrahedron_links_[u], keep, gone);
  }
  // keep's star absorbs gone's.
  auto& n = neighbours_[keep];
  std::vector<int> merged;
  merged.reserve(n.size() + neighbours_[gone].size());
  std::set_union(n.begin(), n.end(), neighbours_[gone].begin(), neighbours_[gone].end(),
                 std::back_inserter(merged));
  merged.erase(
      std::remove_if(merged.begin(), merged.end(), [&](int x) { return x == keep || x == gone; }),
      merged.end());
  n = std::move(merged);
  auto absorb = [&](auto& mine, const auto& theirs) {
    mine.erase(std::remove_if(mine.begin(), mine.end(),
                              [&](const auto& s) { return has_vertex(s, gone); }),
               mine.end());
    for (const auto& s : theirs)
      if (!has_vertex(s, keep)) mine.push_back(s);
    sort_unique(mine);
  };
  absorb(triangle_links_[keep], triangle_links_[gone]);
  absorb(tetrahedron_links_[keep], tetrahedron_links_[gone]);
  neighbours_[gone].clear();
  neighbours_[gone].shrink_to_fit();
  triangle_links_[gone].clear();
  triangle_links_[gone].shrink_to_fit();
  tetrahedron_links_[gone].clear();
  tetrahedron_links_[gone].shrink_to_fit();
  alive_[gone] = 0;

  vertices_ -= 1;
  edges_ += static_cast<long>(neighbours_[keep].size()) - star_edges;
  triangles_ += static_cast<long>(triangle_links_[keep].size()) - star_triangles;
  tetrahedra_ += static_cast<long>(tetrahedron_links_[keep].size()) - star_tetrahedra;
}

void MedialComplex::remove_maximal(const std::vector<int>& s) {
  const int k = static_cast<int>(s.size());
  for (int i = 0; i < k; ++i) {
    const int v = s[i];
    std::array<int, 3> o{};
    for (int j = 0, m = 0; j < k; ++j)
      if (j != i) o[m++] = s[j];
    if (k == 2)
      erase_sorted(neighbours_[v], o[0]);
    else if (k == 3)
      erase_sorted(triangle_links_[v], Pair{o[0], o[1]});
    else
      erase_sorted(tetrahedron_links_[v], Triple{o[0], o[1], o[2]});
  }
  if (k == 2) --edges_;
  if (k == 3) --triangles_;
  if (k == 4) --tetrahedra_;
}

std::vector<Pair> MedialComplex::edge_list() const {
  std::vector<Pair> out;
  for (int v = 0; v < vertex_slots(); ++v)
    for (int u : neighbours_[v])
      if (u > v) out.push_back({v, u});
  return out;
}

std::vector<Triple> MedialComplex::triangle_list() const {
  std::vector<Triple> out;
  for (int v = 0; v < vertex_slots(); ++v)
    for (const auto& p : triangle_links_[v])
      if (p[0] > v) out.push_back({v, p[0], p[1]});
  return out;
}

std::vector<Quad> MedialComplex::tetrahedron_list() const {
  std::vector<Quad> out;
  for (int v = 0; v < vertex_slots(); ++v)
    for (const auto& t : tetrahedron_links_[v])
      if (t[0] > v) out.push_back({v, t[0], t[1], t[2]});
  return out;
}

}  // namespace mg::skeletonize::detail
