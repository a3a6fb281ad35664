#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace papernet {

/// How cut edges get their glue: `Auto` puts a tab on the net where one fits and a separate
/// glue strip elsewhere; `Strips` gives every cut edge a strip; `None` prints no glue at all.
enum class TabMode { Auto, Strips, None };

std::string tab_mode_name(TabMode mode);

/// Candidate moves that pass evaluates in each of its two rounds unless a caller says otherwise
/// (JobOptions::tab_room_budget, PrintOptions::tab_room_budget; TabClearanceOptions).
inline constexpr std::size_t kDefaultTabRoomBudget = 100'000;
/// Most candidate moves a caller may give the pass that makes room for tabs (in Auto mode;
/// PrintOptions::tab_room_budget): about half an hour of search a round.
inline constexpr std::size_t kMaxTabRoomBudget = 100'000'000;

}  // namespace papernet
