// Reading back what print/svg.cpp writes, for tests that check drawings independently of the
// layout's own data.
#pragma once

#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/vec.h"

namespace papernet::test {

/// The text of one SVG group (print/svg.cpp writes each layer as <g id="...">); empty without it.
inline std::string svg_group(const std::string& svg, const std::string& id) {
  const auto start = svg.find("<g id=\"" + id + "\"");
  if (start == std::string::npos) return {};
  return svg.substr(start, svg.find("</g>", start) - start);
}

/// The <polygon> point lists of SVG text, in order.
inline std::vector<std::vector<Vec2>> svg_polygons(const std::string& svg_text) {
  std::vector<std::vector<Vec2>> out;
  static const std::regex polygon("<polygon points=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg_text.begin(), svg_text.end(), polygon);
       it != std::sregex_iterator(); ++it) {
    std::istringstream in((*it)[1].str());
    std::vector<Vec2> poly;
    double x = 0, y = 0;
    char comma = 0;
    while (in >> x >> comma >> y) poly.push_back({x, y});
    out.push_back(std::move(poly));
  }
  return out;
}

/// A <text> of SVG text: its x and y as written (the middle of its baseline, or with `start`,
/// text-anchor="start", its left end), size and text.
struct SvgText {
  double x = 0, y = 0, size = 0;
  std::string text;
  bool start = false;
};

/// The <text> elements of SVG text, in order.
inline std::vector<SvgText> svg_texts(const std::string& svg_text) {
  static const std::regex text(
      "<text x=\"([-0-9.]+)\" y=\"([-0-9.]+)\" font-size=\"([0-9.]+)\"([^>]*)>([^<]*)</text>");
  std::vector<SvgText> out;
  for (auto it = std::sregex_iterator(svg_text.begin(), svg_text.end(), text);
       it != std::sregex_iterator(); ++it)
    out.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]), (*it)[5].str(),
                   (*it)[4].str().find("text-anchor=\"start\"") != std::string::npos});
  return out;
}

/// An axis-aligned box on the page, mm.
struct SvgBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool holds(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  bool overlaps(const SvgBox& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

/// The boxes of the <image> elements of SVG text, in order.
inline std::vector<SvgBox> svg_images(const std::string& svg_text) {
  static const std::regex image(
      "<image x=\"([-0-9.]+)\" y=\"([-0-9.]+)\" width=\"([0-9.]+)\" height=\"([0-9.]+)\"");
  std::vector<SvgBox> out;
  for (auto it = std::sregex_iterator(svg_text.begin(), svg_text.end(), image);
       it != std::sregex_iterator(); ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    out.push_back({x, y, x + std::stod((*it)[3]), y + std::stod((*it)[4])});
  }
  return out;
}

}  // namespace papernet::test
