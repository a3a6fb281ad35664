// Internal to the tab clearance pass (core/tabs/tab_clearance*.cpp): its tuning. Not part of the
// public API.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <numbers>
#include <vector>

#include "core/tabs/tab_clearance.h"
#include "core/unfold/overlap.h"

namespace papernet::tab_clearance_detail {

// Cut edges farther along the cut tree tried per link (see Clearance::candidates).
constexpr std::size_t kFarGlues = 32;
// Vertices walked at most along a hair (see Clearance::hair_links).
constexpr std::size_t kHairSteps = 64;
// A vertex this far from flat (angle defect, radians: 10 degrees) hosts a leaf of the cut tree
// without harm: its slit opens by that angle.
constexpr double kSharpDefect = 10 * std::numbers::pi / 180;
// Tabu search (Clearance::run): how many blocked edges a move may close net, for how many
// steps a move's edges stay tabu, how many sweeps without a new best end a stage, and the
// candidate moves evaluated per step in each stage.
constexpr long long kMaxWorsening = 1;
constexpr int kTenure = 40;
constexpr int kStallSweeps = 3;
// Endgame of the search: restarts from the best net without a new best before it stops, and the
// stage (kStepCaps) a restart begins with.
constexpr int kRestarts = 4;
constexpr std::size_t kRestartLevel = 1;
constexpr std::array<std::size_t, 4> kStepCaps = {50, 200, 800, static_cast<std::size_t>(-1) / 2};
// Moved faces near a move's edge that Clearance::blocked_when_moved tests one by one, at most.
constexpr std::size_t kNearMovedFaces = 32;
// Compound moves (Clearance::try_compound): glues tried per second link.
constexpr std::size_t kCompoundGlues = 16;
// ... and faces tried as the root of its layout (spread over the net).
constexpr std::size_t kRoots = 8;
// Kicks (kick): glues tried per link, moved-face tests of the local repair of each, faces of the
// net per candidate move a kick counts as in the budget, how many blocked edges more than the
// best net's a repaired net may have for a short search from it, and that search's budget as a
// fraction of the round's (1 / kKickSearches: 10,000 candidate moves by default).
constexpr std::size_t kKickGlues = 8;
constexpr std::size_t kKickFacesPerEvaluation = 10;
constexpr std::size_t kKickRepairTests = 5'000;
constexpr std::size_t kKickSlack = 3;
constexpr std::size_t kKickSearches = 10;
// The second round (clear_tab_room) is more of the tabu search when it spent its budget with
// more blocked edges than this left, else kicks.
constexpr std::size_t kSearchOnBlocked = 64;

}  // namespace papernet::tab_clearance_detail
