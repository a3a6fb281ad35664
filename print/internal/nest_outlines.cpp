#include "print/internal/nest_outlines.h"

#include <libnest2d/libnest2d.hpp>

#include <cmath>

namespace papernet::print_detail {
namespace {

bool overlap(const libnest2d::Item& a, const libnest2d::Item& b) {
  ClipperLib::Clipper clipper;
  clipper.AddPath(a.transformedShape().Contour, ClipperLib::ptSubject, true);
  clipper.AddPath(b.transformedShape().Contour, ClipperLib::ptClip, true);
  ClipperLib::Paths common;
  clipper.Execute(ClipperLib::ctIntersection, common, ClipperLib::pftNonZero,
                  ClipperLib::pftNonZero);
  double area = 0;
  for (const auto& p : common) area += std::abs(ClipperLib::Area(p));
  return area > 0;
}

}  // namespace

std::vector<NestedOutline> nest_outlines(const std::vector<std::vector<IntPoint>>& outlines,
                                         std::int64_t width, std::int64_t height) {
  std::vector<libnest2d::Item> items;
  items.reserve(outlines.size());
  for (const auto& outline : outlines) {
    ClipperLib::Path path;
    for (const IntPoint& p : outline) path.push_back({p.x, p.y});
    items.emplace_back(path);
  }
  using libnest2d::BottomLeftPlacer;
  using libnest2d::FirstFitSelection;
  // Outlines come turned to fit the sheet; the placer's own quarter turns are off, because with
  // them libnest2d 5.0 was seen to leave two turned outlines overlapping.
  const libnest2d::NestConfig<BottomLeftPlacer, FirstFitSelection> config{};
  const libnest2d::Box sheet({0, 0}, {width, height});
  std::vector<NestedOutline> out(items.size());
  // Nest; then check every pair on a sheet, and nest those that overlap an earlier one again on
  // sheets of their own (an outline alone on a sheet overlaps nothing), until none overlaps.
  std::vector<std::size_t> todo(items.size());
  for (std::size_t i = 0; i < todo.size(); ++i) todo[i] = i;
  int first_sheet = 0;
  while (!todo.empty()) {
    std::vector<libnest2d::Item> batch;
    for (std::size_t i : todo) batch.push_back(items[i]);
    libnest2d::nest<BottomLeftPlacer, FirstFitSelection>(batch, sheet, 0, config);
    std::vector<std::size_t> again;
    int sheets = 0;
    for (std::size_t k = 0; k < batch.size(); ++k) {
      bool clash = false;
      for (std::size_t j = 0; j < k && !clash && batch[k].binId() >= 0; ++j)
        clash = batch[j].binId() == batch[k].binId() && overlap(batch[j], batch[k]);
      if (clash) {
        again.push_back(todo[k]);
        batch[k].binId(-2);  // off its sheet: later outlines are not checked against it
        continue;
      }
      const auto t = batch[k].translation();
      const int bin = batch[k].binId();
      out[todo[k]] = {bin < 0 ? -1 : first_sheet + bin, static_cast<double>(batch[k].rotation()),
                      t.X, t.Y};
      sheets = std::max(sheets, bin + 1);
    }
    if (again.size() == todo.size()) break;  // cannot happen: the first is alone on its sheet
    first_sheet += sheets;
    todo = std::move(again);
  }
  return out;
}

}  // namespace papernet::print_detail
