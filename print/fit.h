#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "core/tabs/tab_clearance_options.h"
#include "core/unfold/net.h"
#include "core/vec.h"
#include "print/merge_budget.h"

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

/// Pieces grown from single faces instead of cut from a net (docs/print.md, "Fit layout"), as
/// Blender's paper-model exporter grows its islands: every face of `mesh` starts as a piece of
/// its own, laid flat; then the mesh's edges, flattest fold first (concave folds count double,
/// longer edges first among equal folds), each join the two pieces on its sides when the joined
/// piece lies flat without overlap (kOverlapTolerance of the mesh's diagonal) and, at `scale`
/// millimetres per unit, fits `room` as cut_to_fit's pieces do. The pieces are compact where a
/// net's subtrees sprawl. No piece takes faces of two parts (values of `piece`); `cut_links`
/// counts the pieces beyond the parts. Every face must fit `room.room`, or `room.alone` as a piece
/// of its own (listed in `large`; cut_to_fit throws otherwise).
/// With `tab_height` > 0 (model units) a join is also refused when it leaves a cut edge inside
/// the joined piece (a slit: an edge whose two faces were in the two pieces, not glued) where a
/// tab that high (of core/tabs' tab_shapes(`tab_angle_deg`), half the edge on a short one) fits
/// on neither side without overlapping a face of the piece, unless its two sides lie on each
/// other: more, smaller pieces, and tabs instead of glue strips on those cuts. Deterministic:
/// the same mesh grows the same pieces.
/// With `regrow_faces` > 0, the pieces of at most that many faces left when no join is left
/// (small pieces between larger ones, which no join of a whole piece fitted) are taken apart
/// again, and their faces, one at a time, join the pieces around them first, then each other;
/// the result is kept when it has fewer pieces.
FitPieces grow_to_fit(const Mesh& mesh, const std::vector<int>& piece, double scale, FitRoom room,
                      double tab_height = 0, double tab_angle_deg = 45,
                      std::size_t regrow_faces = 0);

/// How much work merge_pieces may do: the Tabu Unfolder's moved-face tests, the tab room pass's
/// evaluations and the merges offered (work, not time: the same pieces on every run), and, where
/// a job's time limit bounds the print, seconds.
struct MergeBudget {
  /// The budget of `tests` tests in all, with a sixth as many tab evaluations (the defaults'
  /// share) and the other bounds at their defaults.
  static MergeBudget of_tests(std::size_t tests) {
    MergeBudget budget;
    budget.tests = tests;
    budget.tab_evaluations = tests / 6;
    return budget;
  }

  /// Unfoldings of a pair from its two pieces' trees glued across one of the edges they share
  /// (edges spread over those they share), before the `tries`.
  int glued = 2;
  int tries = 2;  ///< unfoldings of a pair from the Tabu Unfolder's starts, seeds 1, 2, ...
  std::size_t tests_per_face = 200;         ///< of one unfolding, per face of the pair
  std::size_t iterations_per_face = 20;     ///< rounds of one unfolding, per face of the pair
  std::size_t tests = kDefaultMergeBudget;  ///< of all unfoldings
  /// Candidate moves of the pass that makes room for tabs on a merged piece, per face of it.
  std::size_t tab_evaluations_per_face = 20;
  std::size_t tab_evaluations = kDefaultMergeBudget / 6;  ///< of all those passes
  /// Branches hung elsewhere to make an unfolding that lies flat but does not fit the room fit
  /// it, per face of the pair (print/internal/compact.h; 0: none).
  std::size_t compact_evaluations_per_face = 40;
  /// When no pair merges, a piece split between two of its neighbours (one piece fewer): the
  /// shares of its faces that go to the first, tried in turn until a split unfolds (none: no
  /// splits; three shares, 0.5, 0.25 and 0.75, left as many pieces as one, more slowly:
  /// docs/print.md, "Pieces merged after the search").
  std::vector<double> split_shares{0.5};
  std::size_t split_tests_per_face = 50;  ///< of one unfolding of a side of a split
  /// Merges offered to merge_pieces' `keep`, kept or not.
  std::size_t keeps = 64;
  /// Seconds for the whole merge (0: no bound; the work bounds alone give the same pieces on
  /// every run).
  double seconds = 0;
};

/// `pieces` (of `mesh`, each face's piece in `pieces.piece`, each a tree of `pieces.net`) merged
/// two at a time (docs/print.md, "Fit layout"): two pieces of one part (values of `part`) that
/// share an edge become one when their faces, unfolded anew together by the Tabu Unfolder (from
/// the two pieces' trees glued across a shared edge, `budget.glued` edges, then from its own starts
/// of seeds 1 to `budget.tries`), lie flat without overlap, fit `room` at `scale` millimetres per
/// unit as cut_to_fit's pieces do, and, with `tabs.min_height` > 0, leave room for a tab on every
/// cut inside the piece (core/tabs' edges_without_tab_room). The pairs of the fewest faces are
/// tried first, again after each merge. When no pair merges, a piece is split between two of its
/// neighbours (`budget.split_shares`, the smallest pieces first): its faces nearest the one join
/// it, the rest the other, each side unfolded anew from its piece's tree with the faces it takes
/// hanging towards it, and made when both lie flat and fit as a merged pair must. A piece of a
/// face larger than the room (`pieces.large`) stays as it is. With `keep`, each merge is offered to
/// it (at most `budget.keeps`) and made only when it says yes (the fit search keeps a merge that
/// prints on as many sheets or fewer at a lower cost); a pair refused is not tried again while
/// neither piece changes. With `keep` and `threads` > 1, the pairs after one offered are unfolded
/// on another thread while `keep` runs (one thread more, no more: the offers and pieces are those
/// of one thread; an unfolding made ahead is made again where the budget left has shrunk below
/// what it spent). Deterministic, unless `budget.seconds` stops it. With `progress`, reports
/// phase "merge" after each unfolding and each merge offered, its `phase_fraction` the share used
/// of the budget nearest its end (never decreasing), and throws CancelledException when it is
/// cancelled.
FitPieces merge_pieces(const Mesh& mesh, const std::vector<int>& part, FitPieces pieces,
                       double scale, FitRoom room, const TabClearanceOptions& tabs,
                       const MergeBudget& budget = {},
                       const std::function<bool(const FitPieces&)>& keep = {},
                       Progress* progress = nullptr, int threads = 1);

/// A link of an unfold tree cut by cut_tendrils: `face` made a root, where it hung from `parent`.
struct TendrilCut {
  int face = -1;
  int parent = -1;
};

/// Tendrils of sprawling pieces cut off (docs/print.md, "Tendrils cut off to save a sheet"):
/// `count` times, the unfold-tree link of `pieces` whose cut most shrinks the convex hull of its
/// piece (the piece's hull area less those of the two pieces the cut makes) is cut, a new piece
/// with its own 2D frame unchanged; fewer when no cut shrinks a hull. The pieces are numbered
/// anew by their trees (a piece for each root, in the roots' order by face). Returns the cuts
/// made, in order.
std::vector<TendrilCut> cut_tendrils(FitPieces& pieces, int count);

/// `cut` undone: its face hangs from its parent again, and the pieces are numbered anew.
void undo_tendril_cut(FitPieces& pieces, const TendrilCut& cut);

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
