#include "print/layout.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "print/internal/place_labels.h"

namespace papernet {

std::string tab_mode_name(TabMode mode) {
  switch (mode) {
    case TabMode::Auto:
      return "auto";
    case TabMode::Strips:
      return "strips";
    case TabMode::None:
      return "none";
  }
  return "auto";
}

std::string fit_goal_name(FitGoal goal) { return goal == FitGoal::Pieces ? "pieces" : "sheets"; }

void PrintOptions::validate() const {
  const auto fail = [](const char* option, const std::string& message) {
    throw InvalidOptionException("option_out_of_range", option, message);
  };
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!(scale > 0) && !positive(size_mm)) fail("size_mm", "size must be a positive length");
  if (!std::isfinite(scale) || scale < 0) fail("scale", "scale must be a positive factor");
  if (!std::isfinite(flat_fold_degrees) || flat_fold_degrees < 0 || flat_fold_degrees > 180)
    fail("flat_fold_degrees", "flat fold angle must be between 0 and 180 degrees");
  if (!std::isfinite(tab_height_mm) || tab_height_mm < 0)
    fail("tab_height_mm", "tab height must be >= 0");
  if (!(tab_angle_deg > 0 && tab_angle_deg <= 90))
    fail("tab_angle_deg", "tab angle must be in (0, 90] degrees");
  if (!std::isfinite(min_tab_height_mm) || min_tab_height_mm < 0)
    fail("min_tab_height_mm", "minimum tab height must be >= 0");
  if (!positive(max_label_mm)) fail("max_label_mm", "label size must be positive");
  if (tab_room_budget > kMaxTabRoomBudget)
    fail("tab_room_budget",
         "tab room budget must be at most " + std::to_string(kMaxTabRoomBudget) + " moves");
  if (merge_budget > kMaxMergeBudget)
    fail("merge_budget",
         "merge budget must be at most " + std::to_string(kMaxMergeBudget) + " tests");
}
double print_scale(const Mesh& mesh, const PrintOptions& options) {
  if (options.scale > 0) return options.scale;
  const Vec3 size = bounding_box(mesh).size();
  const double extent = std::max({size.x, size.y, size.z});  // -inf without vertices
  return extent > 0 && std::isfinite(extent) ? options.size_mm / extent : 1;
}

bool makes_tab_room(const PrintOptions& options) {
  return options.tabs == TabMode::Auto && options.tab_height_mm > 0 && options.tab_room_budget > 0;
}

TabClearanceOptions tab_clearance_options(const Mesh& mesh, const PrintOptions& options) {
  TabClearanceOptions clearance;
  const double mm = std::min(options.min_tab_height_mm, options.tab_height_mm);
  clearance.min_height = mm / print_scale(mesh, options);
  clearance.angle_deg = options.tab_angle_deg;
  clearance.time_limit_seconds = options.tab_room_seconds;
  clearance.max_evaluations = options.tab_room_budget;
  return clearance;
}

PrintLayout layout_net(const Mesh& mesh, const Net& net, const PrintOptions& options,
                       const std::vector<int>& piece, const LargeFaces& large,
                       LabelPass label_pass) {
  options.validate();
  if (mesh.faces.empty()) throw InvalidInputException("nothing to print: the mesh has no faces");
  if (net.points.size() != mesh.faces.size() || net.parent.size() != mesh.faces.size())
    throw InvalidInputException("the net has " + std::to_string(net.points.size()) +
                                " faces but the mesh has " + std::to_string(mesh.faces.size()));
  const auto nv = static_cast<int>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (const int v : mesh.faces[f])
      if (v < 0 || v >= nv)
        throw InvalidInputException("mesh face " + std::to_string(f) + " refers to vertex " +
                                    std::to_string(v) + " of " + std::to_string(nv));
  for (std::size_t f = 0; f < net.points.size(); ++f)
    for (const Vec2 p : net.points[f])
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw InvalidInputException("net face " + std::to_string(f) + " has a non-finite point");
  if (!piece.empty() && piece.size() != mesh.faces.size())
    throw InvalidInputException("the net has " + std::to_string(piece.size()) +
                                " faces with a piece but the mesh has " +
                                std::to_string(mesh.faces.size()));
  if (!large.face.empty() && large.face.size() != mesh.faces.size())
    throw InvalidInputException("the net has " + std::to_string(large.face.size()) +
                                " faces marked large or not but the mesh has " +
                                std::to_string(mesh.faces.size()));
  int pieces = 0;
  for (const int p : piece) {
    if (p < 0) throw InvalidInputException("a face has a negative piece");
    pieces = std::max(pieces, p + 1);
  }
  PrintLayout out;
  out.metrics = net_metrics(mesh, net);
  out.scale = print_scale(mesh, options);

  // Rotate into the minimum-area box and scale to millimetres.
  out.faces.resize(net.points.size());
  for (std::size_t f = 0; f < net.points.size(); ++f)
    for (int k = 0; k < 3; ++k)
      out.faces[f][k] = out.scale * rotate(net.points[f][k], out.metrics.box.angle);

  out.edges = classify_edges(mesh, net, {options.flat_fold_degrees});
  print_detail::number_cut_edges(out.faces, out.edges);
  // The label of cut edge `e` on side `s`: across pieces it names the piece its edge glues to
  // (docs/print.md).
  const auto text_of = [&](int e, EdgeSide s) {
    const NetEdge& edge = out.edges[e];
    const int other = s.face == edge.a.face ? edge.b.face : edge.a.face;
    const bool joins = !piece.empty() && other >= 0 && piece[other] != piece[s.face];
    return joins ? std::to_string(edge.cut_index + 1) + "→" + piece_name(piece[other])
                 : print_detail::label_text(edge.cut_index + 1);
  };
  const TabMode mode = options.tab_height_mm > 0 ? options.tabs : TabMode::None;
  std::vector<int> bare;  // cut edges that get no tab on the net
  if (mode == TabMode::Auto) {
    TabOptions tab_options;
    tab_options.height = options.tab_height_mm;
    tab_options.angle_deg = options.tab_angle_deg;
    tab_options.min_height = options.min_tab_height_mm;
    tab_options.large = large;
    // A side whose face holds its label only under the legible size wants the edge's tab: the
    // label moves onto it (make_labels_legible), where a thin face has no room beside its edge.
    // Only where the edge is long enough for a tab over it whose top holds the label at that
    // size (45-degree ends, prefer_min_height tall): elsewhere the preference would move tabs
    // for nothing.
    if (options.labels) {
      tab_options.prefer.assign(3 * out.faces.size(), 0);
      for (int e = 0; e < static_cast<int>(out.edges.size()); ++e) {
        if (out.edges[e].cut_index < 0) continue;
        for (const EdgeSide s : {out.edges[e].a, out.edges[e].b}) {
          if (s.face < 0) continue;
          const auto& tri = out.faces[s.face];
          const std::string text = text_of(e, s);
          const double top =
              norm(tri[(s.k + 1) % 3] - tri[s.k]) - 2 * tab_options.prefer_min_height;
          if (top >= 1.15 * 0.6 * kLegibleLabelMm * label_chars(text) &&
              print_detail::make_label(tri, s, text, options.max_label_mm).size < kLegibleLabelMm)
            tab_options.prefer[3 * s.face + s.k] = 1;
        }
      }
    }
    TabPlacement placed = place_tabs(out.faces, out.edges, tab_options);
    // The preference costs no glue strip: where it leaves more edges without a tab than placing
    // without it does, the tabs are placed without it.
    if (!placed.omitted.empty() && std::find(tab_options.prefer.begin(), tab_options.prefer.end(),
                                             1) != tab_options.prefer.end()) {
      tab_options.prefer.clear();
      if (TabPlacement plain = place_tabs(out.faces, out.edges, tab_options);
          plain.omitted.size() < placed.omitted.size())
        placed = std::move(plain);
    }
    out.tabs = std::move(placed.tabs);
    bare = std::move(placed.omitted);
  } else {
    for (int e = 0; e < static_cast<int>(out.edges.size()); ++e)
      if (out.edges[e].cut_index >= 0) bare.push_back(e);
  }
  if (mode == TabMode::None) {
    out.omitted_tabs = std::move(bare);
  } else {
    StripOptions strip_options;
    strip_options.max_half_width = options.tab_height_mm;
    strip_options.min_half_width =
        std::max(1.0, std::min(options.min_tab_height_mm, options.tab_height_mm));
    out.strips =
        place_strips(out.faces, out.tabs, strip_requests(out.faces, out.edges, bare, strip_options),
                     {}, strip_options);
    for (GlueStrip& s : out.strips) {
      if (!options.labels) continue;
      s.text = print_detail::label_text(out.edges[s.edge].cut_index + 1);
      // As tall as fits a half of the strip, and as long as fits its length.
      const double length = norm(s.corners[1] - s.corners[0]);
      const double half = 0.5 * norm(s.corners[3] - s.corners[0]);
      const double chars = label_chars(s.text);
      s.text_size =
          std::max(kLegibleLabelMm,
                   std::min({options.max_label_mm, 0.6 * half, 0.8 * length / (0.6 * chars)}));
    }
  }

  std::vector<int> tab_of(out.edges.size(), -1);
  for (int t = 0; t < static_cast<int>(out.tabs.size()); ++t) tab_of[out.tabs[t].edge] = t;
  auto side_segment = [&](EdgeSide s) {
    return Segment{out.faces[s.face][s.k], out.faces[s.face][(s.k + 1) % 3], s.face};
  };
  for (int e = 0; e < static_cast<int>(out.edges.size()); ++e) {
    const NetEdge& edge = out.edges[e];
    const bool draw_fold = edge.kind != EdgeKind::Flat || options.draw_flat_folds;
    if (edge.kind != EdgeKind::Cut) {
      if (draw_fold) (edge.fold > 0 ? out.mountain : out.valley).push_back(side_segment(edge.a));
      continue;
    }
    if (edge.cut_index >= 0) ++out.cut_edges;
    for (EdgeSide s : {edge.a, edge.b}) {
      if (s.face < 0) continue;
      const int t = tab_of[e];
      if (t >= 0 && out.tabs[t].side.face == s.face && out.tabs[t].side.k == s.k) {
        const auto& c = out.tabs[t].corners;
        const Segment edge_line = side_segment(s);
        // A tab on part of the edge: the rest of the edge is still cut.
        if (norm(c[1] - edge_line.a) > 0) out.cut.push_back({edge_line.a, c[1], s.face});
        if (norm(edge_line.b - c[0]) > 0) out.cut.push_back({c[0], edge_line.b, s.face});
        out.mountain.push_back({c[1], c[0], s.face});
        out.cut.push_back({c[1], c[2], s.face});
        out.cut.push_back({c[2], c[3], s.face});
        out.cut.push_back({c[3], c[0], s.face});
      } else {
        out.cut.push_back(side_segment(s));
      }
      if (options.labels && edge.cut_index >= 0)
        out.labels.push_back({{}, 0, 0, text_of(e, s), e, s});
    }
  }

  if (label_pass == LabelPass::Placed)
    print_detail::place_labels(out, tab_of, piece, pieces, options);

  // Translate so that everything starts at the origin.
  Box2 box = Box2::empty();
  for (const auto& f : out.faces)
    for (Vec2 p : f) box.add(p);
  for (const Tab& t : out.tabs)
    for (Vec2 p : t.corners) box.add(p);
  for (const GlueStrip& t : out.strips)
    for (Vec2 p : t.corners) box.add(p);
  if (out.faces.empty()) box = {};
  const Vec2 shift = Vec2{0, 0} - box.lo;
  for (auto& f : out.faces)
    for (Vec2& p : f) p = p + shift;
  for (Tab& t : out.tabs)
    for (Vec2& p : t.corners) p = p + shift;
  for (GlueStrip& t : out.strips)
    for (Vec2& p : t.corners) p = p + shift;
  for (auto* list : {&out.cut, &out.mountain, &out.valley, &out.leaders})
    for (Segment& s : *list) s = {s.a + shift, s.b + shift, s.face};
  for (Label& l : out.labels) l.at = l.at + shift;
  for (Label& l : out.piece_labels) l.at = l.at + shift;
  out.size = box.size();
  return out;
}

}  // namespace papernet