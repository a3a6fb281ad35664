#include <algorithm>
#include <string>

#include "core/unfold/net_check.h"

namespace papernet {

NetCheckReport check_pieces(const Mesh& mesh, const Net& net, const std::vector<int>& piece,
                            NetCheckOptions options) {
  const std::size_t nf = mesh.faces.size();
  if (!(options.diagonal > 0)) options.diagonal = bounding_box_diagonal(mesh);
  NetCheckReport out;
  if (piece.size() != nf || net.parent.size() != nf || net.points.size() != nf) {
    out.failures.push_back("the net has " + std::to_string(net.points.size()) + " faces and " +
                           std::to_string(piece.size()) + " piece numbers for " +
                           std::to_string(nf) + " mesh faces");
    out.failure_count = 1;
    return out;
  }
  const int pieces = nf == 0 ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  std::vector<std::vector<int>> faces(std::max(pieces, 0));
  for (std::size_t f = 0; f < nf; ++f) {
    if (piece[f] < 0) {
      out.failures.push_back("face " + std::to_string(f) + " has no piece");
      ++out.failure_count;
      return out;
    }
    faces[piece[f]].push_back(int(f));
  }
  // Each piece as a mesh and net of its own: vertices and faces renumbered, parents too.
  std::vector<int> local(nf, -1), vertex(mesh.vertices.size(), -1);
  for (int p = 0; p < pieces; ++p) {
    Mesh part;
    Net part_net;
    for (std::size_t i = 0; i < faces[p].size(); ++i) local[faces[p][i]] = int(i);
    for (int f : faces[p]) {
      std::array<int, 3> t{};
      for (int c = 0; c < 3; ++c) {
        int& v = vertex[mesh.faces[f][c]];
        if (v < 0) {
          v = int(part.vertices.size());
          part.vertices.push_back(mesh.vertices[mesh.faces[f][c]]);
        }
        t[c] = v;
      }
      part.faces.push_back(t);
      const int parent = net.parent[f];
      const bool inside = parent >= 0 && std::size_t(parent) < nf && piece[parent] == p;
      // A parent in another piece is kept out of range, so that the check names it.
      part_net.parent.push_back(parent < 0 ? -1 : inside ? local[parent] : int(nf + parent));
      part_net.points.push_back(net.points[f]);
    }
    for (int f : faces[p])
      for (int c = 0; c < 3; ++c) vertex[mesh.faces[f][c]] = -1;
    const NetCheckReport r = check_net(part, part_net, options);
    out.failure_count += r.failure_count;
    out.overlapping_pairs += r.overlapping_pairs;
    for (const std::string& message : r.failures)
      if (out.failures.size() < options.max_messages)
        out.failures.push_back("piece " + std::to_string(p) + ": " + message);
  }
  return out;
}

}  // namespace papernet
