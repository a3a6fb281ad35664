#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/unfold/net.h"
#include "core/unfold/overlap.h"

namespace papernet {

/// Tolerances of the net checker, relative to the mesh's bounding-box diagonal.
struct NetCheckOptions {
  double length_tolerance = 1e-6;  ///< edge lengths and glued corners
  /// Overlaps thinner than this are ignored: twice the unfolder's, so that rounding in what the
  /// unfolder accepted never fails the check.
  double overlap_tolerance = 2 * kOverlapTolerance;
  std::size_t max_messages = 20;  ///< failures listed in full; the rest are counted
  /// The length the tolerances are relative to; 0: the bounding-box diagonal of the mesh checked.
  double diagonal = 0;
};

/// What the checker found. `ok()` when nothing failed.
struct NetCheckReport {
  std::vector<std::string> failures;  ///< the first `max_messages` failures, one sentence each
  std::size_t failure_count = 0;      ///< all failures
  std::size_t overlapping_pairs = 0;
  bool ok() const { return failure_count == 0; }
  /// All messages in one string, separated by "; ".
  std::string summary() const;
};

/// Checks that `net` is a valid edge unfolding of `mesh`: every 2D face is congruent to its 3D
/// face with the same (counter-clockwise) orientation (its corners where the 3D face lands, within
/// the length tolerance); exactly one root and parent links that form one spanning tree; each
/// face shares a mesh edge with its parent, placed at the same 2D position in both (glued); and
/// no two faces' interiors intersect (no disk of radius `overlap_tolerance` fits inside both).
/// Every predicate holds for any valid mesh, slivers and faces far larger than the rest
/// included. Independent of the unfolder's incremental structures: every pair of faces whose
/// boxes meet is tested, found through a static bounding-box tree.
NetCheckReport check_net(const Mesh& mesh, const Net& net, const NetCheckOptions& options = {});

/// check_net for a net of several pieces: the faces with the same `piece[f]` must be a valid
/// net (one tree) of the part of `mesh` they cover, in that piece's own frame; pieces are not
/// tested against each other. Failures name the piece. The tolerances stay relative to the whole
/// mesh's diagonal (unless `options.diagonal` says otherwise), as the unfolder and the pieces'
/// growth measure theirs: relative to a small piece's own, they would fail a piece of a large
/// model for rounding the growth accepted (the Menger sponge of level 3 at 400 mm, grown into
/// 644 pieces: one of 20 faces failed).
NetCheckReport check_pieces(const Mesh& mesh, const Net& net, const std::vector<int>& piece,
                            NetCheckOptions options = {});

}  // namespace papernet
