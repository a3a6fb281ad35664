#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "core/errors.h"
#include "print/colour.h"
#include "print/layout.h"
#include "print/pages.h"

namespace papernet {

/// How the net is found (docs/architecture.md): QQ, SEMP and SEQ collapse the mesh with their
/// collapse strategy and unfold progressively; TU unfolds the full mesh with the Tabu Unfolder;
/// AUTO (the default) is QQ that, when its uncollapse stops short of the mesh, finishes the mesh
/// with the Tabu Unfolder from where it stopped (ProgressiveOptions::complete_first).
enum class Strategy { QQ, SEMP, SEQ, TU, AUTO };

std::string strategy_name(Strategy strategy);

/// Which connected parts of a mesh become pieces: every one, or only the largest.
enum class Components { All, Largest };

/// How many faces the net folds into (docs/print.md, "Detail"): `auto` collapses a part denser
/// than a person can build at the print size to the faces they can (engine: buildable_faces);
/// `full` keeps every face; `faces` collapses to that many first (each part its share).
enum class DetailMode { Auto, Full, Faces };

struct Detail {
  DetailMode mode = DetailMode::Auto;
  std::size_t faces = 0;  ///< with DetailMode::Faces
};

/// "auto", "full" or the face count.
std::string detail_name(const Detail& detail);

/// Everything a caller may choose about one unfolding job, the same for the command line and the
/// service. Defaults are what a user who says nothing gets. Parsed and validated before any
/// geometry runs. Each option has one name: `size_mm` in a query or JSON, `--size` on the
/// command line (option_flag).
struct JobOptions {
  Strategy strategy = Strategy::AUTO;
  std::uint64_t seed = 1;
  /// Overrides the collapse target t_f; unset means the paper's formula.
  std::optional<std::size_t> target_faces;
  /// The faces printed: auto, full or a count (collapsed with the strategy's collapses, QQ's
  /// for TU); a collapsed part's net is approximate. `simplify N` is the older name of N.
  Detail detail;
  /// Seconds the whole job may take; unset means the front end's default.
  std::optional<double> time_limit;
  /// Longest side of the model's bounding box in millimetres (exclusive with `scale`).
  std::optional<double> size_mm;
  /// Millimetres per mesh unit (exclusive with `size_mm`); neither set means 200 mm.
  std::optional<double> scale;
  /// A name of named_papers() (print/pages.h), "WxHmm" or "none" (the SVG sized to the net; the
  /// PDF on A4).
  std::string paper = PageOptions{}.paper.name;
  double margin_mm = PageOptions{}.margin_mm;
  /// Shared strip between neighbouring tiles of a net larger than a page (layout tile).
  double overlap_mm = PageOptions{}.overlap_mm;
  /// Pages: fit (pieces larger than a page cut along folds, or grown anew from single faces where
  /// that saves sheets, every piece nested whole onto the fewest sheets; a face larger than a
  /// sheet is an error) or tile (each part one piece, tiled across pages to tape together).
  /// Unset: fit, or tile when a face is larger than a sheet (the result says so).
  std::optional<PageLayoutMode> layout;
  /// What the fit layout saves first: sheets (the default), or pieces and glue strips to cut out.
  FitGoal prefer = PrintOptions{}.prefer;
  /// Glue: auto (tabs on the net where they fit, after making room for them; strips for the
  /// rest), strips (only strips) or none.
  TabMode tabs = PrintOptions{}.tabs;
  /// Tallest tab and widest strip half; 0 means no glue.
  double tab_height_mm = PrintOptions{}.tab_height_mm;
  /// Lowest tab printed (or half a shorter edge).
  double min_tab_height_mm = PrintOptions{}.min_tab_height_mm;
  /// Candidate moves the pass that makes room for tabs evaluates at most in each of its two
  /// rounds; 0 skips it. The job's time limit (at least a second for the pass) also ends it.
  std::size_t tab_room_budget = kDefaultTabRoomBudget;
  /// Moved-face tests the merge of pieces after the fit search spends at most (layout fit); 0
  /// skips it. The job's time limit also ends it.
  std::size_t merge_budget = PrintOptions{}.merge_budget;
  /// Folds flatter than this many degrees are not drawn.
  double flat_fold_degrees = PrintOptions{}.flat_fold_degrees;
  bool labels = PrintOptions{}.labels;  ///< matching numbers on both sides of each cut edge
  /// Print the model's colour (textures, material and vertex colours) on SVG and PDF pages
  /// (docs/colour.md, "Printing"); false prints line art.
  bool colour = true;
  /// Resolution of the printed colour, dots per inch; later pages print lower when the time limit
  /// would pass (docs/colour.md, "Time limit").
  double dpi = kDefaultColourDpi;
  /// A first page with a map of the sheets, the pieces on each and the build order (layout fit
  /// only). Unset: with more than one piece.
  std::optional<bool> overview;
  /// The kit's name, printed on every page beside its number, as the overview's title and as
  /// the PDF's title: at most kMaxTitleChars characters of UTF-8, no control characters, spaces
  /// at its ends dropped. Empty: none.
  std::string title;
  /// Every connected part its own piece (all), or only the largest part (the result says what
  /// it dropped).
  Components components = Components::All;
  /// Refuse what repair would fix (non-manifold edges, pinches, degenerate or flipped faces,
  /// several parts unless `components` is largest) instead of repairing it.
  bool strict = false;
  /// The service POSTs the job's final status here when the job ends (docs/security.md
  /// "Webhooks"): http://HOST[:PORT][/PATH]. The command line refuses it.
  std::optional<std::string> callback_url;
};

inline constexpr std::size_t kMaxTitleChars = 80;

/// Limits a front end puts on options (the service's from its configuration).
struct OptionsLimits {
  double max_time_limit = 600;
  std::size_t max_target_faces = 2'000'000;
};

/// Options from URL query parameters (`strategy=QQ&seed=3`). Names not listed here are
/// rejected, so a typo never silently means a default.
/// \throw InvalidOptionException naming the first fault.
JobOptions parse_options_query(const std::multimap<std::string, std::string>& params,
                               const OptionsLimits& limits = {});

/// The options part's limits: a flat object needs neither.
inline constexpr std::size_t kMaxOptionsJsonBytes = 64 << 10;
inline constexpr int kMaxOptionsJsonDepth = 16;

/// Options from a JSON object (the `options` part of a multipart upload). Longer or deeper
/// documents than the limits above are refused (malformed_options) before they are built.
/// \throw InvalidOptionException naming the first fault.
JobOptions parse_options_json(std::string_view text, const OptionsLimits& limits = {});

/// The command-line flag of option `name`: "--" and the name with dashes, less a trailing "_mm"
/// (lengths take units there: `--size 15cm`).
std::string option_flag(std::string_view name);

/// True when `flag` is the flag of a yes/no option, which may stand alone (`--labels`) or take
/// yes/no, true/false, on/off or 1/0.
bool is_boolean_flag(std::string_view flag);

/// Applies one command-line option (`--size`, "150mm"). A boolean flag given alone has no value.
/// Returns false when `flag` names no option. Call validate_options once all are applied.
/// \throw InvalidOptionException naming the option.
bool apply_option_flag(JobOptions& options, std::string_view flag,
                       std::optional<std::string_view> value);

/// One line (or two) per option for a command's --help: flag, value and what it does.
std::string options_help();

/// Checks ranges and combinations, including the print's (a margin that leaves no room on the
/// paper). Called by both parsers. \throw InvalidOptionException naming the first fault.
void validate_options(const JobOptions& options, const OptionsLimits& limits = {});

/// Canonical JSON of the options (every field, stable key order): what the job record shows
/// and what identifies "the same options" for result reuse.
nlohmann::json options_to_json(const JobOptions& options);

/// The print's own options for a job (print/layout.h, print/pages.h); the one place that maps
/// one to the other. `paper` none gives A4 pages (for the PDF) and `has_paper` false.
PrintOptions print_options(const JobOptions& options);
PageOptions page_options(const JobOptions& options);
bool has_paper(const JobOptions& options);

}  // namespace papernet
