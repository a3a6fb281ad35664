#pragma once

#include <cstddef>
#include <optional>

#include "core/mesh/decimate.h"
#include "core/mesh/mesh.h"
#include "core/progress.h"

namespace papernet {

/// How far simplify_mesh collapses.
struct SimplifyTarget {
  /// Collapse to at most this many faces (0: keep them all).
  std::size_t faces = 0;
  /// Then, when > 0, go on collapsing in steps of a sixth of the faces while more edges than
  /// `short_edges_allowed` times the faces are shorter than this; a step that would take the
  /// surface farther than `max_distance` from `mesh` (two-sided Hausdorff, in its units) is not
  /// taken: half as many collapses are tried instead, down to one, which ends it when it too
  /// moves the surface that far.
  double short_edge = 0;
  double short_edges_allowed = 0;
  double max_distance = 0;
  /// Tunnels whose loop around (shortest_tunnel_loop, core/mesh/tunnels.h) is at most this long
  /// are plugged (0: none). Before the collapse to `faces`, when that moved the surface farther
  /// than `max_distance`: the most collapsed mesh within it is plugged and collapsed to `faces`
  /// instead, kept when it moves the surface less. And when the steps find no collapse left,
  /// unless plugging takes the surface farther than `max_distance`, and the steps go on. When
  /// neither plugs nor flips (`thin_face`) help, the short edges themselves are collapsed,
  /// shortest first, into their middle or an end, where that keeps the surface within
  /// `max_distance` and leaves no face lower than the lower of `thin_face` and the lowest face
  /// around the edge, and the steps go on.
  double max_tunnel_loop = 0;
  /// Faces lower than this over their longest edge have edges flipped (thicken_thin_faces,
  /// core/mesh/thin_faces.h), the flips of one round moving the surface at most a quarter of
  /// `max_distance`: when the steps find no collapse left, and at the end. 0: no flips.
  double thin_face = 0;
  /// When true, a part that is a thin plate, within `max_distance` of one of its sides
  /// (plate_side, core/mesh/thin_plates.h), becomes that side (an open surface, one layer of
  /// card): the part as given, before the collapse, and once more the collapsed mesh at the end;
  /// not a side that folds over itself at its border (the faces round a border vertex turning
  /// through more than a full turn).
  bool thin_plates = false;
  /// Seconds the steps for short edges may take (each measures the distance to `mesh`, which
  /// on a dense mesh of slivers adds up to seconds); when they are spent, the mesh collapsed so
  /// far is returned, and the result then depends on the machine's speed. <= 0: no limit.
  double seconds = 0;
};

/// A low-poly version of `mesh` to print instead of it: collapsed with `strategy` (legal
/// collapses only, as decimate) to at most `target.faces` faces, or as far as legal collapses
/// go, then further while it has short edges (SimplifyTarget), with ids of its own. None when
/// that is not fewer faces than `mesh`: then print `mesh` itself. Fewer, larger faces have sharper
/// vertices and longer edges, so more cut edges have room for a glue tab (docs/tabs.md) and a
/// label. Reports phase "collapse". \throw InvalidInputException when `mesh` is not a manifold,
/// oriented triangle mesh. \throw CancelledException when `progress` asks to stop.
std::optional<Mesh> simplify_mesh(const Mesh& mesh, CollapseStrategy strategy,
                                  const SimplifyTarget& target, Progress& progress);

/// The number of `mesh`'s edges (each counted once) shorter than `length`.
std::size_t count_short_edges(const Mesh& mesh, double length);

}  // namespace papernet
