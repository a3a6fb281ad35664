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

}  // namespace papernet::test
