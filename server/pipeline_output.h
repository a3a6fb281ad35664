#pragma once

#include <cstddef>
#include <string>

#include "api/options.h"
#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/unfold/net.h"
#include "core/unfold/net_check.h"

namespace papernet::server {

/// The print files of a net, in memory, and the layout's figures for the net JSON.
struct PrintFiles {
  std::string svg;  ///< one page when the net fits the paper, else the whole net in one drawing
  std::string pdf;  ///< tiled onto the job's paper (A4 when it asked for none)
  std::string glb;  ///< the mesh the net folds into
  int pages = 1;
  std::size_t cut_edges = 0;  ///< interior cut edges (each gets one tab or one strip)
  std::size_t tabs = 0;       ///< glue tabs on the net
  std::size_t strips = 0;     ///< separate glue strips (cut edges without room for a tab)
  double coverage = 0;
  double aspect_ratio = 1;
};

/// Makes `net` the net to print and deliver: with tab mode auto, changed so that more cut edges
/// have room for a glue tab at the job's print size (api make_tab_room) when that net passes the
/// net checker; else left as it is. Returns the checker's report on the net it leaves, so that
/// no net is checked twice. The pass stops after `seconds` (> 0) with the best net so far.
/// \throw CancelledException.
NetCheckReport make_room_for_tabs(const Mesh& mesh, Net& net, const JobOptions& options,
                                  double seconds, Progress& progress);

/// Lays out `net` for print with the job's options (size or scale, paper, margin, tabs, flat
/// folds) and writes SVG, PDF and GLB. Kept apart from the net JSON writer: api/net_json.h and
/// core/metrics.h both declare a `NetMetrics`.
/// \throw InvalidInputException when the options leave no room on the paper.
PrintFiles render_print_files(const Mesh& mesh, const Net& net, const JobOptions& options);

}  // namespace papernet::server
