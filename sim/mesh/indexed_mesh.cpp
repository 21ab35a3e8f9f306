#include "sim/mesh/indexed_mesh.h"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

namespace mdhd::mesh {

std::uint32_t IndexedMesh::index(const MeshVertex& v) {
  const auto [it, added] = index_.try_emplace(v.key, static_cast<std::uint32_t>(positions_.size()));
  if (added) positions_.push_back(v.position);
  return it->second;
}

void IndexedMesh::triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                           bool exterior) {
  triangles_.push_back({index(a), index(b), index(c)});
  exterior_.push_back(exterior ? 1 : 0);
}

std::size_t IndexedMesh::memoryBytes() const {
  return positions_.capacity() * sizeof(glm::dvec3) +
         triangles_.capacity() * sizeof(triangles_[0]) + exterior_.capacity() +
         index_.size() * (sizeof(VertexKey) + sizeof(std::uint32_t) + 2 * sizeof(void*));
}

EdgeReport checkEdges(const IndexedMesh& mesh) {
  EdgeReport r;
  // Per undirected edge: uses from the lower index to the higher, and back.
  std::unordered_map<std::uint64_t, std::array<int, 2>> uses;
  uses.reserve(mesh.triangles().size() * 2);
  for (const auto& t : mesh.triangles()) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) ++r.collapsed;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      ++uses[key][a < b ? 0 : 1];
    }
  }
  for (const auto& [key, n] : uses) {
    ++r.edges;
    const int total = n[0] + n[1];
    if (total == 1)
      ++r.open;
    else if (total > 2)
      ++r.overused;
    else if (n[0] != 1)
      ++r.sameDirection;
  }
  return r;
}

std::int64_t nonManifoldVertices(const IndexedMesh& mesh) {
  // The link of a vertex: for each of its triangles, the opposite edge.
  // A manifold vertex's link is one cycle.
  const std::size_t n = mesh.positions().size();
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> link(n);
  for (const auto& t : mesh.triangles())
    for (int i = 0; i < 3; ++i) link[t[i]].push_back({t[(i + 1) % 3], t[(i + 2) % 3]});
  std::int64_t bad = 0;
  std::unordered_map<std::uint32_t, std::uint32_t> next;
  for (std::size_t v = 0; v < n; ++v) {
    if (link[v].empty()) continue;
    next.clear();
    bool ok = true;
    for (const auto& [a, b] : link[v]) ok = next.emplace(a, b).second && ok;
    std::size_t steps = 0;
    std::uint32_t at = link[v][0].first;
    do {
      const auto it = next.find(at);
      if (it == next.end()) {
        ok = false;
        break;
      }
      at = it->second;
      ++steps;
    } while (at != link[v][0].first && steps <= link[v].size());
    if (!ok || steps != link[v].size()) ++bad;
  }
  return bad;
}

double enclosedVolume(const IndexedMesh& mesh) {
  if (mesh.positions().empty()) return 0.0;
  const glm::dvec3 o = mesh.positions().front();  // near the mesh: less cancellation
  double sum = 0.0;
  for (const auto& t : mesh.triangles()) {
    const glm::dvec3 a = mesh.positions()[t[0]] - o, b = mesh.positions()[t[1]] - o,
                     c = mesh.positions()[t[2]] - o;
    sum += glm::dot(a, glm::cross(b, c));
  }
  return sum / 6.0;
}

double surfaceArea(const IndexedMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles()) {
    const glm::dvec3& a = mesh.positions()[t[0]];
    sum += 0.5 * glm::length(glm::cross(mesh.positions()[t[1]] - a, mesh.positions()[t[2]] - a));
  }
  return sum;
}

double smallestTriangleArea(const IndexedMesh& mesh) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles()) {
    const glm::dvec3& a = mesh.positions()[t[0]];
    smallest = std::min(smallest, 0.5 * glm::length(glm::cross(mesh.positions()[t[1]] - a,
                                                               mesh.positions()[t[2]] - a)));
  }
  return smallest;
}

}  // namespace mdhd::mesh
