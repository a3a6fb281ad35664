// A mesh's loose parts (core/mesh/repair.h, `split_components`): faces joined through shared
// vertices, each part a mesh of its own.
#include "core/mesh/repair.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

#include "core/union_find.h"

namespace papernet {

std::vector<Mesh> split_components(const Mesh& mesh, std::vector<std::vector<int>>* faces_of) {
  const std::size_t nf = mesh.faces.size();
  UnionFind parts(nf);
  std::vector<int> vertex_face(mesh.vertices.size(), -1);
  for (std::size_t f = 0; f < nf; ++f)
    for (int v : mesh.faces[f]) {
      if (vertex_face[v] >= 0) parts.unite(int(f), vertex_face[v]);
      vertex_face[v] = int(f);
    }
  // Parts by size, largest first; ties in the order of their first face.
  std::vector<int> index(nf, -1), size, first;
  for (std::size_t f = 0; f < nf; ++f) {
    int& i = index[parts.find(int(f))];
    if (i < 0) {
      i = int(size.size());
      size.push_back(0);
      first.push_back(int(f));
    }
    ++size[i];
  }
  std::vector<int> rank(size.size());
  std::iota(rank.begin(), rank.end(), 0);
  std::stable_sort(rank.begin(), rank.end(), [&](int a, int b) { return size[a] > size[b]; });
  std::vector<int> slot(size.size());
  for (std::size_t r = 0; r < rank.size(); ++r) slot[rank[r]] = int(r);
  std::vector<Mesh> out(size.size());
  std::vector<int> remap(mesh.vertices.size(), -1);
  for (std::size_t f = 0; f < nf; ++f) {
    Mesh& part = out[slot[index[parts.find(int(f))]]];
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      int& r = remap[mesh.faces[f][c]];
      if (r < 0) {  // a vertex belongs to one part only
        r = int(part.vertices.size());
        part.vertices.push_back(mesh.vertices[mesh.faces[f][c]]);
      }
      t[c] = r;
    }
    part.faces.push_back(t);
    if (faces_of) {
      faces_of->resize(out.size());
      (*faces_of)[slot[index[parts.find(int(f))]]].push_back(int(f));
    }
  }
  return out;
}

}  // namespace papernet
