// Internal to the tab clearance pass (core/tabs/tab_clearance*.cpp). Not part of the public API.
#pragma once

#include "core/mesh/mesh.h"
#include "core/tabs/internal/pass_progress.h"
#include "core/tabs/tab_clearance.h"

namespace papernet::tab_clearance_detail {

/// The pass's second round as kicks (core/tab_clearance_kick.cpp), after Clearance::run on
/// `result.net`: for each blocked edge in turn, a swap that opens it (a link cut at one of its
/// ends, one of the kKickGlues nearest cut edges across glued that leaves no new flat leaf) is
/// made whether or not it overlaps; Unfolding::repair_locally removes the overlaps (the kick is
/// dropped when it cannot); a repaired net with at most kKickSlack blocked edges more than
/// `result`'s gets a tabu search of a tenth of the budget (kKickSearches) that visits only the
/// edges near what moved (focus_), and replaces `result` when it ends with fewer. Sweeps until one
/// makes no kick, `options.max_evaluations` more candidate moves are spent (a kick counts as 1 +
/// faces / kKickFacesPerEvaluation of them, its search as what it evaluates), or `seconds_left`
/// runs out (only when options.time_limit_seconds > 0). Deterministic otherwise.
void kick(const Mesh& mesh, const TabClearanceOptions& options, double seconds_left,
          PassProgress& progress, TabClearanceResult& result);

}  // namespace papernet::tab_clearance_detail
