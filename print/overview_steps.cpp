// The overview's build order: each piece's step ("P3 glues to P1, P2"), its lines broken to fit,
// flowed into columns (print/internal/overview_parts.h).

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "print/internal/overview_parts.h"

namespace papernet::print_detail {
namespace {

constexpr double kStepGap = 4;  // between columns of the build order, in text heights

/// The build order's steps, each as lines no wider than `width` at `size` (the lines after a
/// step's first kStepIndent text heights narrower, to be indented): "P3 glues to P1, P2" (the
/// pieces before it that it shares an edge with), broken after a comma onto more lines where it
/// is wider ("P3 glues to P1," at least on its first; with `at_spaces`, at every space where even
/// that is wider), "P1: start here", "P7: start a new part".
std::vector<std::vector<std::string>> build_steps(const Overview& overview, double width,
                                                  double size, bool at_spaces) {
  std::vector<std::vector<std::string>> steps;
  const int count = static_cast<int>(overview.page.size());
  for (int p = 0; p < count; ++p) {
    std::vector<int> earlier;
    for (const int q : overview.graph.joins[p])
      if (q < p) earlier.push_back(q);
    std::vector<std::string> step =
        p == 0 ? std::vector{piece_name(p) + ": start here"}
        : earlier.empty()
            ? std::vector{piece_name(p) + ": start a new part"}
            : wrap(piece_name(p) + " glues to", earlier, width, size, kStepIndent * size);
    // On paper too narrow for its first line, at every space (every line as narrow as those
    // indented).
    if (at_spaces && text_width(step.front(), size) > width) {
      std::string text;
      for (const std::string& line : step) text += (text.empty() ? "" : " ") + line;
      step = wrap_words(text, width - kStepIndent * size, size);
    }
    steps.push_back(std::move(step));
  }
  return steps;
}

// The most columns of the build order on a page.
constexpr int kMostStepColumns = 8;

/// The width of the build order's lines in `columns` columns on a page `width` wide at `size`:
/// each column kStepGap text heights wider than its lines.
double step_room(double width, double size, int columns) {
  return width / columns - kStepGap * size;
}

}  // namespace

std::vector<std::string> wrap(const std::string& head, const std::vector<int>& pieces, double width,
                              double size, double indent) {
  std::vector<std::string> lines{head};
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const std::string name = piece_name(pieces[i]) + (i + 1 < pieces.size() ? "," : "");
    std::string& line = lines.back();
    const std::string longer = line + " " + name;
    const double room = lines.size() > 1 ? width - indent : width;
    if (line.size() > head.size() && text_width(longer, size) > room)
      lines.push_back(name);
    else
      line = longer;
  }
  return lines;
}

std::vector<std::string> wrap_words(const std::string& text, double width, double size) {
  std::vector<std::string> lines;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    const std::string word = text.substr(at, end - at);
    if (!lines.empty() && text_width(lines.back() + " " + word, size) <= width)
      lines.back() += " " + word;
    else
      lines.push_back(word);
    at = end + 1;
  }
  return lines;
}

std::vector<std::vector<std::string>> column_steps(const Overview& overview, double width,
                                                   double size, int columns) {
  return build_steps(overview, step_room(width, size, columns), size, columns == 1);
}

std::vector<StepLine> step_lines(const Overview& overview, double width, double size, int columns) {
  std::vector<StepLine> lines;
  for (std::vector<std::string>& step : column_steps(overview, width, size, columns))
    for (std::size_t i = 0; i < step.size(); ++i) lines.push_back({std::move(step[i]), i > 0});
  return lines;
}

StepFlow flow_steps(const std::vector<std::vector<std::string>>& steps, StepFlow at, int columns,
                    int rows, std::vector<StepLine>* lines) {
  const auto whole = static_cast<std::size_t>(rows);
  for (int c = 0; c < columns && at.step < steps.size(); ++c) {
    std::size_t left = whole;
    while (left > 0 && at.step < steps.size()) {
      const std::vector<std::string>& step = steps[at.step];
      const std::size_t rest = step.size() - at.line;
      if (rest > left && at.line == 0 && step.size() <= whole && left < whole) break;
      const std::size_t take = std::min(rest, left);
      if (lines)
        for (std::size_t i = at.line; i < at.line + take; ++i) lines->push_back({step[i], i > 0});
      left -= take;
      at.line += take;
      if (at.line == step.size()) at = {at.step + 1, 0};
    }
    if (lines && c + 1 < columns && at.step < steps.size())
      lines->insert(lines->end(), left, StepLine{});
  }
  return at;
}

int step_columns(const Overview& overview, double width, double size, bool break_steps) {
  int best = 1;
  std::size_t best_rows = std::numeric_limits<std::size_t>::max();
  for (int columns = 1; columns <= kMostStepColumns; ++columns) {
    const double room = step_room(width, size, columns);
    std::size_t lines = 0;
    bool fits = true, whole = true;
    for (const std::vector<std::string>& step : column_steps(overview, width, size, columns)) {
      fits = fits && text_width(step.front(), size) <= room;
      whole = whole && step.size() == 1;
      lines += step.size();
    }
    if (columns > 1 && !(fits && (whole || break_steps))) break;
    const std::size_t rows = (lines + columns - 1) / columns;
    if (rows < best_rows) best = columns, best_rows = rows;
    if (lines <= static_cast<std::size_t>(columns)) break;  // one row: no fewer
  }
  return best;
}

}  // namespace papernet::print_detail
