#pragma once

#include <string>

namespace papernet {

/// What the fit layout saves first when it chooses how to cut the net into pieces: `Sheets`, a
/// sheet fewer worth up to kPiecesPerSheet more pieces and glue strips to cut out; `Pieces`, a
/// piece or strip fewer worth up to that many more sheets (docs/print.md, "Fit layout").
enum class FitGoal { Sheets, Pieces };

/// How many pieces and strips a sheet is worth against them (FitGoal::Sheets), and sheets a
/// piece or strip (FitGoal::Pieces).
inline constexpr double kPiecesPerSheet = 20;

std::string fit_goal_name(FitGoal goal);

}  // namespace papernet
