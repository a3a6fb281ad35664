#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "print/tab_mode.h"

namespace papernet {

/// Collapse strategy of Progressive Mesh Unfolding (DESIGN.md §1.3); TU unfolds the full mesh.
enum class Strategy { QQ, SEMP, SEQ, TU };

/// Paper sheet the SVG/PDF is tiled onto.
enum class PaperSize { A4, Letter, A3, None };

std::string strategy_name(Strategy strategy);
std::string paper_name(PaperSize paper);

/// Everything a client may choose about one unfolding job. Defaults are what a user who says
/// nothing gets. Parsed and validated before any geometry runs.
struct JobOptions {
  Strategy strategy = Strategy::QQ;
  std::uint64_t seed = 1;
  /// Overrides the collapse target t_f; unset means the paper's formula.
  std::optional<std::size_t> target_faces;
  /// Unfold and print a low-poly version of the mesh, collapsed to this many faces first (the
  /// strategy's collapses, QQ's for TU; fewer, larger faces leave room for more glue tabs); the
  /// result is then approximate. Unset, or not below the mesh's face count: the mesh itself.
  std::optional<std::size_t> simplify;
  /// Seconds the unfolder may spend; unset means the server's default.
  std::optional<double> time_limit;
  /// Longest side of the model's bounding box in millimetres (exclusive with `scale`).
  std::optional<double> size_mm;
  /// Millimetres per mesh unit (exclusive with `size_mm`); neither set means 1.
  std::optional<double> scale;
  PaperSize paper = PaperSize::A4;
  double margin_mm = 10;
  /// Glue: auto (tabs on the net where they fit, after making room for them; strips for the
  /// rest), strips (only strips) or none. JSON/query `true` means auto, `false` none.
  TabMode tabs = TabMode::Auto;
  /// Candidate moves the pass that makes room for tabs (tabs auto) evaluates at most in each of
  /// its two rounds; 0 skips it. More opens more edges on dense meshes; the job's time limit (at
  /// least a second for the pass) also ends it.
  std::size_t tab_room_budget = kDefaultTabRoomBudget;
  /// Folds flatter than this many degrees are not drawn.
  double flat_fold_degrees = 1;
  bool keep_largest_component = false;
};

/// Limits the service puts on options (from its configuration).
struct OptionsLimits {
  double max_time_limit = 600;
  std::size_t max_target_faces = 2'000'000;
};

/// An option that cannot be accepted. `code` is stable for clients: unknown_option,
/// invalid_option_value, option_out_of_range, conflicting_options, malformed_options.
class OptionsError : public std::invalid_argument {
 public:
  OptionsError(std::string code, std::string option, const std::string& message)
      : std::invalid_argument(message), code_(std::move(code)), option_(std::move(option)) {}
  const std::string& code() const { return code_; }
  /// The offending option's name ("" when the whole document is at fault).
  const std::string& option() const { return option_; }

 private:
  std::string code_;
  std::string option_;
};

/// Options from URL query parameters (`strategy=QQ&seed=3`). Names not listed here are
/// rejected, so a typo never silently means a default.
/// \throw OptionsError naming the first fault.
JobOptions parse_options_query(const std::multimap<std::string, std::string>& params,
                               const OptionsLimits& limits = {});

/// The options part's limits: a flat object needs neither.
inline constexpr std::size_t kMaxOptionsJsonBytes = 64 << 10;
inline constexpr int kMaxOptionsJsonDepth = 16;

/// Options from a JSON object (the `options` part of a multipart upload). Longer or deeper
/// documents than the limits above are refused (malformed_options) before they are built.
/// \throw OptionsError naming the first fault.
JobOptions parse_options_json(std::string_view text, const OptionsLimits& limits = {});

/// Checks ranges and combinations. Called by both parsers.
/// \throw OptionsError naming the first fault.
void validate_options(const JobOptions& options, const OptionsLimits& limits = {});

/// Canonical JSON of the options (every field, stable key order): what the job record shows
/// and what identifies "the same options" for result reuse.
nlohmann::json options_to_json(const JobOptions& options);

}  // namespace papernet
