#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "api/net_json.h"
#include "api/options.h"
#include "core/io/load.h"
#include "core/mesh/validate.h"
#include "core/progress.h"

namespace papernet {

/// What a job unfolds: the model's bytes and the files it refers to (a .gltf's buffers).
struct JobInput {
  std::string mesh;
  MeshFormat format = MeshFormat::Unknown;  ///< Unknown: sniffed from the bytes
  std::map<std::string, std::string> external_files;
};

/// The front end's limits and defaults.
struct PipelineLimits {
  std::size_t max_bytes = std::size_t{64} << 20;  ///< of the mesh file
  std::size_t max_faces = 1'000'000;              ///< after triangulation
  double default_time_limit = 60;                 ///< seconds, when the options set none
};

/// The documents a run writes; the net JSON always.
struct DocumentRequest {
  bool svg = false;        ///< Documents::svg
  bool svg_pages = false;  ///< Documents::svg_pages
  bool pdf = false;
  bool glb = false;
  bool obj = false;
  bool print() const { return svg || svg_pages || pdf; }
};

struct Documents {
  std::string net_json;  ///< papernet.net (api/net_json.h), one line
  /// One SVG: the page when the net fits one sheet of the paper, else the whole net in one
  /// drawing (also without paper).
  std::string svg;
  /// One SVG per page; the whole net in one when there is no paper.
  std::vector<std::string> svg_pages;
  std::string pdf;       ///< one page per sheet (A4 when there is no paper)
  std::string glb, obj;  ///< the mesh the net folds into
};

/// The print's figures, from its layout.
struct PrintSummary {
  int pages = 0;           ///< pages printed, the overview's included
  bool overview = false;   ///< page 1 is an overview of the others (layout fit)
  int overview_pages = 0;  ///< pages 1 to this are the overview (more than one: many sheets)
  std::string layout;      ///< "fit" or "tile" (page_layout_name)
  int pieces = 0;          ///< pieces printed: with layout fit, after cutting them to fit a sheet
  int cut_links = 0;       ///< folds cut so that every piece fits a sheet (layout fit)
  /// Why the layout is not the one asked for (a face larger than a sheet: tiled), or empty.
  std::string layout_note;
  std::size_t cut_edges = 0;     ///< interior cut edges (each gets one tab or one strip)
  std::size_t tabs = 0;          ///< glue tabs on the net
  std::size_t strips = 0;        ///< separate glue strips (cut edges without room for a tab)
  std::size_t tabs_omitted = 0;  ///< cut edges without glue (tabs none)
  std::size_t labels = 0;        ///< edge numbers printed (two per glued edge)
  double smallest_label_mm = 0;  ///< text height of the smallest (0 without labels)
  std::size_t small_labels = 0;  ///< labels under kLegibleLabelMm (print/labels.h)
};

/// What the pass that makes room for glue tabs did (core/tabs), and why edges stay without room.
struct TabRoomSummary {
  std::size_t blocked_before = 0, blocked_after = 0;  ///< cut edges without room for a tab
  std::size_t moves = 0, kicks = 0, evaluations = 0;
  double seconds = 0;
  /// Of the edges still blocked: those at a leaf of the cut tree at a vertex where no leaf can
  /// have room, and the interior vertices where one can (core/tabs/tab_clearance_report.h).
  std::size_t leaves_without_room = 0, leaf_room_vertices = 0, interior_vertices = 0;
  bool rejected = false;  ///< its net failed the net check (a bug): the unfolder's net was kept
};

/// Everything a run produced.
struct UnfoldOutcome {
  NetDocument net;  ///< the net and the mesh it folds into, as the net JSON has them
  MeshFormat format = MeshFormat::Unknown;  ///< of the input file (the print's views: up)
  bool simplified = false;     ///< the mesh was collapsed to `simplify` faces before unfolding
  std::size_t iterations = 0;  ///< of the Tabu Unfolder
  std::optional<TabRoomSummary> tab_room;  ///< when the pass ran
  std::optional<PrintSummary> print;       ///< when a print document was asked for
  /// Per face of `net.mesh`, the colour of faces of approximate pieces from the input surface
  /// nearest to them, for the print (empty: none baked; docs/colour.md, "Printing").
  std::vector<std::vector<ColourTriangle>> baked_colour;
  Documents documents;
};

/// The pipeline's progress hook: the core algorithms' reports (phases load, validate, collapse,
/// unfold, uncollapse, tabs, write), cancellation, and intermediate results.
class PipelineProgress : public Progress {
 public:
  /// An overlap-free net of a coarser mesh while the unfolder works, with the run's documents
  /// (at most every two seconds). Only called when wants_intermediates().
  virtual void intermediate_outcome(const UnfoldOutcome&) {}
  virtual bool wants_intermediates() const { return false; }
};

/// What the pipeline makes of an input before it unfolds it (`papernet info`): the problems of
/// the mesh as loaded, then what repair did (unless strict) and the parts that become pieces, or
/// why it is refused.
struct InputReport {
  MeshFormat format = MeshFormat::Unknown;
  std::size_t raw_vertices = 0;  ///< vertices as the file has them, before welding
  ValidationReport as_loaded;    ///< the welded mesh as the file has it
  std::vector<NetRepair> repairs;
  NetInput repaired;       ///< counts after repair
  std::size_t pieces = 0;  ///< the parts that would be unfolded (one with components=largest)
  std::optional<std::string> refusal;  ///< why it cannot be unfolded, when it cannot
};

/// Loads, repairs and validates `input` as run_pipeline does, without unfolding it.
/// \throw IOException, LimitExceededException (unreadable, unsupported, too large).
InputReport inspect_input(const JobInput& input, const JobOptions& options,
                          const PipelineLimits& limits = {});

/// The one pipeline of papernet (docs/architecture.md), for the command line and the service:
/// load, validate, (simplify), unfold by the job's strategy, measure an approximation's distance,
/// make room for glue tabs, check the net, and write the documents asked for. `options` must
/// have passed validate_options. A part with no overlap-free net in one piece within the time
/// limit, not even of a coarser mesh, or with none at all (a dual graph that is a tree, whose one
/// edge unfolding overlaps), is unfolded in several pieces (warning "unfolded_in_pieces"): every
/// mesh that passes validation gets a net.
/// \throw IOException (unreadable; LimitExceededException over a limit), InvalidMeshException
///        (the mesh cannot be unfolded, with the validator's report),
///        InvalidOptionException (options the print refuses), CancelledException; a net that
///        fails the net check is a bug: std::logic_error.
UnfoldOutcome run_pipeline(const JobInput& input, const JobOptions& options,
                           const PipelineLimits& limits, const DocumentRequest& documents,
                           PipelineProgress& progress);

}  // namespace papernet
