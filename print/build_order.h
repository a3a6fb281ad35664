#pragma once

#include <vector>

#include "core/mesh/mesh.h"

namespace papernet {

/// Which pieces glue to which: two pieces are neighbours when a cut edge of the mesh joins a
/// face of one to a face of the other. `joins[p]` holds p's neighbours, ascending, and
/// `edges[p]` the number of such edges to each (same order).
struct PieceGraph {
  std::vector<std::vector<int>> joins;
  std::vector<std::vector<int>> edges;
};

/// The piece graph of `mesh` with each face's piece in `piece` (pieces 0 .. max + 1): edges
/// with exactly two faces, by their vertices.
PieceGraph piece_graph(const Mesh& mesh, const std::vector<int>& piece);

/// The pieces numbered in a build order (docs/print.md, "Build order"): first the largest
/// piece (by `area`, one entry per piece; ties: the lower number); then, again and again, the
/// piece that shares the most cut edges with the pieces numbered so far (ties: the larger, then
/// the lower number), so that every piece glues to one numbered before it whenever the graph
/// allows; a part that shares no edge with those starts again from its largest piece. Returns
/// each piece's new number.
std::vector<int> build_order(const PieceGraph& graph, const std::vector<double>& area);

/// Renumbers `piece` (each face's piece) by `order` (each old piece's new number).
void renumber_pieces(std::vector<int>& piece, const std::vector<int>& order);

}  // namespace papernet
