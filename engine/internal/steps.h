// Private to engine/: the pipeline's steps, each with its input and output, in the order
// run_pipeline (engine/pipeline.cpp) calls them.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "api/net_json.h"
#include "api/options.h"
#include "core/io/load.h"
#include "core/mesh/colour.h"
#include "core/mesh/mesh.h"
#include "core/mesh/simplify.h"
#include "core/progress.h"
#include "core/unfold/net.h"
#include "core/unfold/net_check.h"
#include "engine/pipeline.h"

namespace papernet::engine_detail {

/// The input as parts to unfold: loaded, repaired (unless strict), validated, split.
struct Prepared {
  std::vector<Mesh> parts;  ///< largest first
  NetInput input;           ///< of the repaired mesh, every part counted
  std::vector<NetRepair> repairs;
  /// Each part's colour, per face as its mesh (empty without colour); materials and textures
  /// are those of `colour`, shared by every part.
  std::vector<MeshColour> part_colours;
  MeshColour colour;  ///< the materials and textures (its per-face vectors left empty)
  MeshFormat format = MeshFormat::Unknown;  ///< of the file read
};

/// Loads `job` within `limits` (engine/prepare.cpp).
/// \throw IOException naming the fault, LimitExceededException.
LoadedMesh load_input(const JobInput& job, const PipelineLimits& limits, Progress& progress);

/// Repairs (unless strict), validates and splits what was loaded; what cannot be unfolded
/// fails here. \throw InvalidMeshException (with the validator's report), CancelledException.
Prepared prepare(LoadedMesh loaded, const JobOptions& options, Progress& progress);

/// A net of several pieces grown from single faces (unfold_piece, when the unfolder found no
/// overlap-free net in one piece): each face's piece, from 0, and how many; `overlaps` is what
/// the unfolder's best single piece had left. `tree`: the part's dual graph is a tree, so its one
/// edge unfolding, which overlaps, is the only net in one piece there is (`overlaps` unset).
struct GrownPieces {
  std::vector<int> piece;
  std::size_t pieces = 0;
  std::size_t overlaps = 0;
  bool tree = false;
};

/// One part unfolded into one piece (engine/unfold_piece.cpp), or into grown pieces.
struct Piece {
  Mesh mesh;  ///< what the net folds into (a coarser mesh when approximate)
  Net net;
  bool complete = true;
  bool simplified = false;
  double hausdorff = 0;
  std::size_t iterations = 0;
  std::optional<GrownPieces> grown;  ///< none when `net` is one tree
};

/// Millimetres per model unit of the print of `parts` (print_scale of them all).
double parts_print_scale(const std::vector<Mesh>& parts, const JobOptions& options);

/// The faces a person can build of `part` printed at `scale` (engine/detail.cpp): its printed
/// area over that of an equilateral face of the smallest buildable edge; at least 100 (a small part
/// keeps its shape).
std::size_t buildable_faces(const Mesh& part, double scale);

/// How far `part` is collapsed before it is unfolded, by the job's `detail`: full not at all,
/// N to the part's share of N (by faces, of `all_faces`), auto to buildable_faces when the part
/// has clearly more, then on while edges print too short for a label (docs/print.md, "Detail").
SimplifyTarget detail_target(const Mesh& part, const JobOptions& options, double scale,
                             std::size_t all_faces);

/// Checks that the print of `parts` at `scale` is one a layout holds: the model's surface as
/// printed at most 20 m², and on paper at most 1,000 sheets' printable area (engine/detail.cpp).
/// \throw InvalidOptionException "print_too_large", naming the size that prints.
void check_print_size(const std::vector<Mesh>& parts, const JobOptions& options, double scale);

/// With detail auto, leaves out of `prepared` the parts with folds (and their colours) whose
/// bounding box's diagonal prints under 10 mm at `scale`, never the largest; a flat part stays
/// (engine/detail.cpp, kSmallestPartMm): the warning "small_parts_left_out" counting them, or
/// none. The result's `input` still counts every part.
std::optional<NetRepair> leave_out_small_parts(Prepared& prepared, const JobOptions& options,
                                               double scale);

/// Seconds a step gets at least (a time limit of 0 means none to the algorithms): the
/// progressive unfolder then returns the coarsest net it finds at once.
inline constexpr double kLeastSeconds = 1e-3;

/// The time the steps after a part's unfold take (run_pipeline): seconds per face of its net, of
/// which `reserved` are already outside the unfold's seconds (ProgressiveOptions, the same names).
struct AfterUnfold {
  double per_face = 0;
  double reserved = 0;
};

/// Unfolds `part` with the job's strategy within `seconds`, less what the steps `after` it need
/// for the net it reaches (a low-poly version collapsed as `detail` says, when that collapses).
/// When no overlap-free net in one piece is found, not even of a coarser mesh, the mesh is
/// unfolded in several pieces instead, grown from single faces as the print grows its pieces
/// (print/grow.h, grow_to_fit; `Piece::grown`). \throw CancelledException.
Piece unfold_piece(const Mesh& part, const JobOptions& options, const SimplifyTarget& detail,
                   double seconds, const AfterUnfold& after, std::size_t input_faces,
                   Progress& progress);

/// The net checker's report on `piece`'s net: check_net, or check_pieces when it is grown pieces.
NetCheckReport check_piece(const Piece& piece);

/// Changes `piece`'s cuts so that more of its cut edges have room for a glue tab, within
/// `seconds` less `seconds_per_strip` for each edge still without room (the print's time for its
/// glue strip), when the job prints tabs; keeps the new net only when it passes the net checker.
/// `piece`'s net must be one tree (not grown).
/// Adds what it did to `summary`. Returns the checker's report on the net it leaves.
NetCheckReport make_room_for_tabs(Piece& piece, const JobOptions& options, double seconds,
                                  double seconds_per_strip, Progress& progress,
                                  std::optional<TabRoomSummary>& summary);

/// The warning a result carries when `detail` full or N printed parts clearly denser than
/// buildable_faces ("detail_unbuildable", counting them); none with detail auto.
std::optional<NetRepair> detail_warning(const std::vector<Piece>& pieces,
                                        const std::vector<Mesh>& parts, const JobOptions& options,
                                        double scale);

/// Ways of making a print's pieces that the fit search lays out at once (each is laid out and
/// nested on its own, and that is most of the search's time).
constexpr int kFitSearchThreads = 2;

/// How many times slower than the machine the pipeline's times per face were measured on this
/// one runs (engine/pipeline.cpp): timed once per process (about 12 ms), at least a quarter.
double machine_slowness();

/// The pieces as one document: their meshes and nets side by side (engine/documents.cpp).
NetDocument assemble(const std::vector<Piece>& pieces, const Prepared& input,
                     const JobOptions& options);

/// The documents of `outcome.net` that `request` asks for; fills `outcome.print` when it asks
/// for a print. Printed on paper, `outcome.net` becomes the net as printed (its pieces cut to fit
/// a sheet, its `print` placements) before the net JSON is written. Progress: phase "layout" (a
/// print's pieces cut to fit, tabs, nesting), then "write", each with its phase_fraction. The
/// print may take `seconds` (what is left of the job's time limit): a fit layout tries several
/// cuts while half of them last, at least one, and keeps the one that needs the fewest sheets for
/// its pieces (docs/print.md, "Fit layout"), laying out `search_threads` of them at a time (the
/// choice is the same for any number); the pages' colour is drawn at a lower resolution where
/// the pages would not be written by then (docs/colour.md, "Time limit").
/// \throw InvalidOptionException when the print refuses the options.
void write_documents(const JobOptions& options, const DocumentRequest& request,
                     UnfoldOutcome& outcome, double seconds, Progress& progress,
                     int search_threads = kFitSearchThreads);

}  // namespace papernet::engine_detail
