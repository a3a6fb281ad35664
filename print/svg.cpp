#include "print/svg.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/io/image.h"

namespace papernet {

namespace {

/// A number in mm with 3 decimals, without trailing zeros.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

/// A polyline as SVG path data: "Mx yLx yLx y".
std::string path_data(const std::vector<Vec2>& points) {
  std::string out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    out.append(i ? "L" : "M");
    out.append(num(points[i].x));
    out.push_back(' ');
    out.append(num(points[i].y));
  }
  return out;
}

struct LayerStyle {
  Layer layer;
  const char* id;
  const char* style;
  const char* path_style = "";  ///< extra attributes of the layer's open polylines
  const char* text_style = "";  ///< extra attributes of the layer's text
};

constexpr LayerStyle kLayers[] = {
    {Layer::Faces, "faces", "fill=\"#f3f6fb\" stroke=\"none\""},
    {Layer::Tabs, "tabs", "fill=\"#e2e2e2\" stroke=\"none\""},
    {Layer::Strips, "strips",
     "fill=\"#fbf1d3\" stroke=\"#000000\" stroke-width=\"0.25\" "
     "font-family=\"sans-serif\" text-anchor=\"middle\"",
     " fill=\"none\" stroke=\"#777777\" stroke-width=\"0.15\" stroke-dasharray=\"1 0.8\"",
     " fill=\"#333333\""},
    {Layer::Cut, "cut",
     "fill=\"none\" stroke=\"#000000\" stroke-width=\"0.25\" "
     "stroke-linecap=\"round\""},
    {Layer::Mountain, "mountain",
     "fill=\"none\" stroke=\"#c0392b\" stroke-width=\"0.2\" "
     "stroke-dasharray=\"2 1\""},
    {Layer::Valley, "valley",
     "fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"0.2\" "
     "stroke-dasharray=\"2 0.7 0.4 0.7\""},
    {Layer::Leaders, "leaders",
     "fill=\"none\" stroke=\"#333333\" stroke-width=\"0.15\" stroke-linecap=\"round\""},
    {Layer::Labels, "labels",
     "fill=\"#333333\" font-family=\"sans-serif\" "
     "text-anchor=\"middle\""},
    {Layer::Marks, "marks",
     "fill=\"#777777\" stroke=\"#777777\" stroke-width=\"0.15\" "
     "stroke-dasharray=\"1 1\" font-family=\"sans-serif\" "
     "text-anchor=\"middle\""},
};

}  // namespace

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string write_svg(const PageDrawing& d,
                      const std::vector<std::pair<std::string, std::string>>& metadata) {
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << num(d.width)
    << "mm\" height=\"" << num(d.height) << "mm\" viewBox=\"0 0 " << num(d.width) << ' '
    << num(d.height) << "\">\n";
  if (!d.title.empty()) o << "<title>" << xml_escape(d.title) << "</title>\n";
  o << "<metadata><papernet xmlns=\"https://papernet.invalid/ns/1\"";
  for (const auto& [k, v] : metadata)
    o << " data-" << xml_escape(k) << "=\"" << xml_escape(v) << '"';
  o << "/></metadata>\n";
  o << "<defs><clipPath id=\"printable\"><rect x=\"" << num(d.clip_lo.x) << "\" y=\""
    << num(d.clip_lo.y) << "\" width=\"" << num(d.clip_hi.x - d.clip_lo.x) << "\" height=\""
    << num(d.clip_hi.y - d.clip_lo.y) << "\"/></clipPath></defs>\n";
  for (const LayerStyle& ls : kLayers) {
    const bool clipped = ls.layer != Layer::Marks;
    o << "<g id=\"" << ls.id << "\" " << ls.style
      << (clipped ? " clip-path=\"url(#printable)\"" : "") << ">\n";
    std::string path;  // open polylines of a layer go into one path
    for (const Shape& s : d.shapes) {
      if (s.layer != ls.layer || s.key) continue;
      if (!s.text.empty()) {
        const Vec2 c = s.points[0];
        // The text's visual centre sits about 0.35 em above its baseline.
        o << "<text x=\"" << num(c.x) << "\" y=\"" << num(c.y + 0.35 * s.size) << "\" font-size=\""
          << num(s.size) << (s.light ? "\" fill=\"#ffffff" : "")
          << (s.start ? "\" text-anchor=\"start" : "") << "\" stroke=\"none\" transform=\"rotate("
          << num(s.angle_deg) << ' ' << num(c.x) << ' ' << num(c.y) << ")\"" << ls.text_style << ">"
          << xml_escape(s.text) << "</text>\n";
      } else if (s.closed) {
        o << "<polygon points=\"";
        for (std::size_t i = 0; i < s.points.size(); ++i)
          o << (i ? " " : "") << num(s.points[i].x) << ',' << num(s.points[i].y);
        o << "\"/>\n";
      } else if (s.light) {  // a line over a dark colour, as light text is
        o << "<path d=\"" << path_data(s.points) << "\" stroke=\"#ffffff\"" << ls.path_style
          << "/>\n";
      } else {
        path.append(path_data(s.points));
      }
    }
    if (!path.empty()) o << "<path d=\"" << path << '"' << ls.path_style << "/>\n";
    o << "</g>\n";
    if (ls.layer == Layer::Tabs && !d.images.empty()) {  // colour over the faces and tabs
      o << "<g id=\"colour\" clip-path=\"url(#printable)\">\n";
      for (const PageImage& image : d.images)
        o << "<image x=\"" << num(image.at.x) << "\" y=\"" << num(image.at.y) << "\" width=\""
          << num(image.width) << "\" height=\"" << num(image.height)
          << "\" preserveAspectRatio=\"none\" href=\"data:image/png;base64,"
          << encode_base64(encode_png(image.surface.get())) << "\"/>\n";
      o << "</g>\n";
    }
  }
  // The key's samples live in the margin: each in its layer's style, unclipped.
  std::string key;
  for (const Shape& s : d.shapes) {
    if (!s.key) continue;
    const auto ls = std::find_if(std::begin(kLayers), std::end(kLayers),
                                 [&](const LayerStyle& l) { return l.layer == s.layer; });
    key.append("<path d=\"")
        .append(path_data(s.points))
        .append("\" ")
        .append(ls->style)
        .append(ls->path_style)
        .append("/>\n");
  }
  if (!key.empty()) o << "<g id=\"key\">\n" << key << "</g>\n";
  o << "</svg>\n";
  return o.str();
}

std::vector<std::pair<std::string, std::string>> layout_metadata(const PrintLayout& layout,
                                                                 int pages) {
  return {{"faces", std::to_string(layout.faces.size())},
          {"cut-edges", std::to_string(layout.cut_edges)},
          {"tabs", std::to_string(layout.tabs.size())},
          {"strips", std::to_string(layout.strips.size())},
          {"tabs-omitted", std::to_string(layout.omitted_tabs.size())},
          {"scale-mm-per-unit", num(layout.scale)},
          {"width-mm", num(layout.size.x)},
          {"height-mm", num(layout.size.y)},
          {"coverage", num(layout.metrics.coverage)},
          {"aspect-ratio", num(layout.metrics.aspect_ratio)},
          {"pages", std::to_string(pages)}};
}

std::string write_net_svg(const PrintLayout& layout, double margin_mm, const PrintColour* colour,
                          const std::string& title) {
  PageDrawing drawing = draw_unpaged(layout, margin_mm, colour);
  drawing.title = title;
  return write_svg(drawing, layout_metadata(layout, 1));
}

std::vector<std::string> write_page_svgs(const PrintLayout& layout, const PageLayout& pages,
                                         const PrintColour* colour) {
  std::vector<std::string> out;
  const int n = static_cast<int>(pages.pages.size());
  for (int i = 0; i < n; ++i)
    out.push_back(write_page_svg(layout, draw_page(layout, pages, i, colour), i, n));
  return out;
}

std::string write_page_svg(const PrintLayout& layout, const PageDrawing& page, int index,
                           int pages) {
  auto meta = layout_metadata(layout, pages);
  meta.emplace_back("page", std::to_string(index + 1));
  return write_svg(page, meta);
}

}  // namespace papernet
