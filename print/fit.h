#pragma once

#include <string>
#include <vector>

#include "core/unfold/net.h"
#include "core/vec.h"

// The fit layout's pieces and the room they fit (docs/print.md, "Fit layout"): a net cut into
// pieces that fit a sheet, and the hull tests every way of making pieces shares. The other ways
// and steps: print/grow.h (pieces grown from single faces), print/tendrils.h (tendrils cut off),
// print/merge.h (pieces merged after the search).

namespace papernet {

/// The pieces of a net cut so that each fits a sheet (docs/print.md, "Fit layout": the first step
/// of the print path, pieces → tabs and strips → nesting → pages → drawing).
struct FitPieces {
  Net net;                 ///< the net with the links that were cut made roots (parent -1)
  std::vector<int> piece;  ///< piece of each face: the input's pieces, then the new ones
  int pieces = 0;
  int cut_links = 0;  ///< unfold-tree links cut (each a new piece and a new glued edge)
  /// Faces too large for the room with tabs that fit the sheet as a piece of their own (each
  /// 1 in this per-face list is such a piece): their tabs hang from the faces beside them where
  /// they can (print/tabs.h, LargeFaces).
  std::vector<char> large;
};

/// The room a piece has on a sheet (width x height, mm, at any turn).
struct FitRoom {
  Vec2 room;  ///< for a piece with its tabs all round it
  /// For a single face that is larger than `room`: the sheet less what the nesting needs, tabs
  /// not counted (they go on the faces beside it). Zero: `room`.
  Vec2 alone;
};

/// Cuts the pieces of `net` (each face's piece in `piece`, each piece one tree of `parent`
/// links, in its own 2D frame) along unfold-tree links until every piece, at `scale` millimetres
/// per unit, fits a `room` (width x height, mm) box in some orientation: a piece fits when the
/// box of its convex hull along one of the hull's edges fits `room` either way round. Greedy from
/// the leaves: a face keeps its children's remaining subtrees while they fit together and cuts
/// off the largest ones (by hull area) when they do not, so a piece that fits is never cut and
/// the pieces cut off are as large as the room allows. With `shrink` below 1, pieces are cut to
/// fit `shrink` x `room` instead (smaller pieces nest onto fewer sheets: docs/print.md, "Fit
/// layout"); a face larger than that is a piece of its own, as long as it fits `room`. A face
/// larger than `room.room` that fits `room.alone` at some turn is a piece of its own too, listed
/// in `large`. Then every cut link whose two pieces fit `glue` x `room` together (`shrink` x
/// `room` when `glue` is smaller) at some turn is glued back, the smallest joined piece first,
/// until none is left.
/// \throw InvalidOptionException ("face_too_large", option "size_mm") naming a face that fits
///        no room, its size, and the largest model size (`model_mm` is the model's size at
///        `scale`) at which every face fits.
FitPieces cut_to_fit(const Net& net, const std::vector<int>& piece, double scale, FitRoom room,
                     const std::string& paper_name, double model_mm, double shrink = 1,
                     double glue = 0);

/// The largest size of the model (`model_mm` now, at `scale` millimetres per unit) at which two
/// faces of `net` linked by its unfold tree, laid flat as the net lays them, fit `room` together
/// as cut_to_fit fits a piece (the box of their convex hull along one of its edges, either way
/// round). Where it is below `model_mm`, no two faces fit that room together at this size (the
/// merge after the search may still join two whose tabs, only where they go, fit the sheet).
/// 0 when the net has no link.
double largest_size_joining_faces(const Net& net, double scale, Vec2 room, double model_mm);

/// The area of the convex polygon `hull` (convex_hull's).
double hull_area(const std::vector<Vec2>& hull);

/// True when the convex polygon `hull` (counter-clockwise) fits a `room` box turned along one of
/// its edges, either way round.
bool hull_fits(const std::vector<Vec2>& hull, Vec2 room);

/// True when the convex polygon `hull` fits a `room` box at some turn: hull_fits, or turned by a
/// multiple of a quarter degree (a long triangle fits a sheet across it, along none of its edges,
/// as the nesting turns it: print/nest.h).
bool hull_fits_turned(const std::vector<Vec2>& hull, Vec2 room);

}  // namespace papernet
