#include "print/print_output.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

#include "core/errors.h"
#include "core/io/write_mesh.h"
#include "print/pdf.h"
#include "print/svg.h"

namespace papernet {

namespace {

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw IOException("cannot write '" + path + "'");
}

}  // namespace

bool apply_output_option(std::string_view name, std::string_view value, OutputOptions& options) {
  auto number = [&](double lo, double hi) {
    double v = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (ec != std::errc() || end != value.data() + value.size() || !(v >= lo && v <= hi))
      throw InvalidInputException(std::string(name) + ": expected a number from " +
                                  std::to_string(lo) + " to " + std::to_string(hi) + ", got '" +
                                  std::string(value) + "'");
    return v;
  };
  if (name == "--size") {
    options.print.size_mm = parse_length_mm(value);
    options.print.scale = 0;
  } else if (name == "--scale") {
    options.print.scale = number(1e-9, 1e9);
  } else if (name == "--paper") {
    options.paper = value != "none";
    if (options.paper) options.page.paper = parse_paper(value);
  } else if (name == "--margin") {
    options.page.margin_mm = value == "0" ? 0 : parse_length_mm(value);
  } else if (name == "--overlap") {
    options.page.overlap_mm = value == "0" ? 0 : parse_length_mm(value);
  } else if (name == "--tab-height") {
    options.print.tab_height_mm = value == "0" ? 0 : parse_length_mm(value);
  } else if (name == "--tabs") {
    options.print.tabs = parse_tab_mode(value);
  } else if (name == "--min-tab-height") {
    options.print.min_tab_height_mm = value == "0" ? 0 : parse_length_mm(value);
  } else if (name == "--tab-room") {
    if (value != "on" && value != "off")
      throw InvalidInputException("--tab-room: expected on or off, got '" + std::string(value) +
                                  "'");
    options.print.tab_room = value == "on";
  } else if (name == "--tab-room-budget") {
    const double moves = number(0, static_cast<double>(kMaxTabRoomBudget));
    if (moves != std::floor(moves))
      throw InvalidInputException("--tab-room-budget: expected a whole number, got '" +
                                  std::string(value) + "'");
    options.print.tab_room_budget = static_cast<std::size_t>(moves);
  } else if (name == "--flat-angle") {
    options.print.flat_angle_deg = number(0, 180);
  } else if (name == "--labels") {
    if (value != "on" && value != "off")
      throw InvalidInputException("--labels: expected on or off, got '" + std::string(value) + "'");
    options.print.labels = value == "on";
  } else {
    return false;
  }
  return true;
}

std::string output_options_help() {
  return "  --size LEN         longest side of the folded model (default 200mm)\n"
         "  --scale F          millimetres per model unit (instead of --size)\n"
         "  --paper P          A4 (default), A3, Letter, WxHmm, or none (SVG sized to the net)\n"
         "  --margin LEN       page margin (default 10mm)\n"
         "  --overlap LEN      overlap between tiles of a net larger than a page (default 10mm)\n"
         "  --tabs MODE        auto (default): a glue tab on the net where one fits, else a\n"
         "                     separate glue strip; strips: strips only; none: no glue\n"
         "  --tab-height LEN   tallest glue tab, widest strip half (default 6mm; 0: no tabs)\n"
         "  --min-tab-height LEN  lowest tab printed, or half a shorter edge (default 2mm)\n"
         "  --tab-room on|off  change the cuts so more edges have room for a tab (default on;\n"
         "                     with --tabs auto; the net JSON written with it is that net)\n"
         "  --tab-room-budget N  candidate moves of that change, in each of its two rounds\n"
         "                     (default 100000; 0: none; dense meshes get more tabs with more,\n"
         "                     10-40 us a move)\n"
         "  --flat-angle DEG   folds flatter than this are not drawn (default 1)\n"
         "  --labels on|off    edge labels (default on)\n";
}

bool is_print_output(const std::string& path) {
  const std::string ext = extension(path);
  return ext == "svg" || ext == "pdf" || ext == "glb" || ext == "obj";
}

WrittenOutput write_output_file(const std::string& path, const Mesh& mesh, const Net& net,
                                const OutputOptions& options) {
  const std::string ext = extension(path);
  WrittenOutput out;
  if (ext == "glb" || ext == "obj") {
    write_file(path, ext == "glb" ? write_glb(mesh) : write_obj(mesh));
    out.files = {path};
    return out;
  }
  if (ext != "svg" && ext != "pdf")
    throw InvalidInputException("unknown output type '" + path +
                                "': use .svg, .pdf, .glb, .obj (or .json for the net)");
  PrintLayout layout = layout_net(mesh, net, options.print);
  out.pages = 1;
  out.tabs = layout.tabs.size();
  out.strips = layout.strips.size();
  out.tabs_omitted = layout.omitted_tabs.size();
  if (ext == "svg" && !options.paper) {
    write_file(path, write_net_svg(layout, options.page.margin_mm));
    out.files = {path};
    return out;
  }
  const PageLayout pages = paginate(layout, options.page);
  out.pages = static_cast<int>(pages.pages.size());
  if (ext == "pdf") {
    write_file(path, write_pdf(layout, pages));
    out.files = {path};
    return out;
  }
  const std::vector<std::string> svgs = write_page_svgs(layout, pages);
  if (svgs.size() == 1) {
    write_file(path, svgs[0]);
    out.files = {path};
    return out;
  }
  const std::string stem = path.substr(0, path.size() - 4);
  for (std::size_t i = 0; i < svgs.size(); ++i) {
    out.files.push_back(stem + "-" + std::to_string(i + 1) + ".svg");
    write_file(out.files.back(), svgs[i]);
  }
  return out;
}

}  // namespace papernet
