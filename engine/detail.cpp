// How many faces each part is printed with, and how large a print may be (docs/print.md, "Detail"
// and "Print size").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/dual_graph.h"
#include "engine/internal/steps.h"
#include "print/layout.h"

namespace papernet::engine_detail {
namespace {

// The printed edge of the smallest faces a person builds without tweezers: a face of this edge
// holds a 1.5 mm label beside each side, and its edges have room for a glue tab. Tuned on
// prints of the Duck and of scans (docs/print.md, "Detail").
constexpr double kBuildableEdgeMm = 18;

// The area never collapses a part below this many faces: a small part (a wheel of a truck) keeps
// its shape rather than become a tetrahedron. Only short edges take it further (below).
constexpr std::size_t kMinDetailFaces = 100;

// The printed edge under which a cut edge has no room for its 1.5 mm label (three digits) beside
// it, nor a glue tab a person can fold: auto collapses on while more edges than kShortEdgesAllowed
// of the faces are that short (slivers and small features of CAD parts), as long as the surface
// moves at most kDetailDistanceMm from the model's: a feature smaller than the shortest edge a
// person builds goes. Tuned on the CAD parts and the milk truck of tests/data (docs/print.md,
// "Detail").
constexpr double kShortEdgeMm = 3;
constexpr double kShortEdgesAllowed = 0.01;
constexpr double kDetailDistanceMm = 3;

// A tunnel through a part (a hole through a plate) whose loop around prints shorter than this is
// plugged when the collapse for short edges is stuck: a hole under 6 mm across, with walls of
// 3 mm edges and their glue tabs, is not built in card.
constexpr double kTunnelLoopMm = 6 * kShortEdgeMm;

// A face printed lower than this over its longest edge (a sliver along a CAD part's edge, a fan
// of them on a flat side) holds its labels only under 1.5 mm: its edges are flipped where that
// makes it thicker, within a quarter of the distance bound (core/mesh/thin_faces.h).
constexpr double kThinFaceMm = kShortEdgeMm;

// A part with folds whose bounding box's diagonal prints under this is left out with detail auto:
// its edges print at a few millimetres, too short for a glue tab a person folds or a 1.5 mm
// label beside them, and a part that small is not folded and glued in card (the ogre's teeth and
// claws at 200 mm, 2 to 7 mm across, printed 114 labels under 1.5 mm). A flat part (a decal) is
// only cut out, and stays. The truck's smallest parts, its lights, are 13 mm across
// (docs/print.md, "Detail").
constexpr double kSmallestPartMm = 10;

// A part is collapsed only when it has this much more than the buildable faces: a model a
// little denser is printed as it is rather than approximated.
constexpr double kDetailSlack = 1.25;

// The most a print holds (docs/print.md, "Print size"): the model's surface as printed, and the
// sheets of its paper that surface fills at the least (each sheet's printable area covered
// whole). The layout's grids hold cells of millimetres over the paper, so a larger print took
// minutes and gigabytes: the Duck at 20 m on A0 paper 69 s and 10.5 GB with a 15 s limit, at
// 100 m on A4 still running after 2 minutes. 20 m² is about 400 A4 sheets filled whole.
constexpr double kMostPrintSurfaceMm2 = 20e6;
constexpr double kMostPrintSheets = 1000;

double area(const Mesh& mesh) {
  double a = 0;
  for (const auto& t : mesh.faces) {
    const Vec3 p = mesh.vertices[t[0]], q = mesh.vertices[t[1]], r = mesh.vertices[t[2]];
    a += 0.5 * norm(cross(q - p, r - p));
  }
  return a;
}

// True when two faces of `part` meet at an edge at more than a flat fold: their normals' angle's
// cosine under `flat` (a flat part, a decal, is only cut out).
bool folds(const Mesh& part, double flat) {
  const DualGraph graph = build_dual_graph(part);
  for (int f = 0; f < static_cast<int>(part.faces.size()); ++f)
    for (const int g : graph.neighbour[f]) {
      if (g <= f) continue;  // each edge once; -1 on a boundary
      const Vec3 n = face_normal(part, f), m = face_normal(part, g);
      const double lengths = norm(n) * norm(m);
      if (lengths > 0 && dot(n, m) < flat * lengths) return true;
    }
  return false;
}

// `v` rounded to a whole number with thousands separated by commas.
std::string whole(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.0f", std::round(v));
  const std::string digits = buf;
  const std::size_t sign = !digits.empty() && digits[0] == '-' ? 1 : 0;
  std::string out = digits.substr(0, sign);
  for (std::size_t i = sign; i < digits.size(); ++i) {
    if (i > sign && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// `v` > 0 rounded down to three significant digits (at least its whole part).
std::string down_to_3_digits(double v) {
  if (v >= 100) return whole(std::floor(v));
  const double unit = std::pow(10.0, std::floor(std::log10(v)) - 2);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g", std::floor(v / unit) * unit);
  return buf;
}

}  // namespace

void check_print_size(const std::vector<Mesh>& parts, const JobOptions& options, double scale) {
  double surface = 0;  // mm²
  Box3 box = Box3::empty();
  for (const Mesh& part : parts) {
    surface += area(part) * scale * scale;
    for (const Vec3& v : part.vertices) box.add(v);
  }
  const double sheet = has_paper(options) ? [&] {
    const PageOptions page = page_options(options);
    return std::max(0.0, page.paper.width - 2 * page.margin_mm) *
           std::max(0.0, page.paper.height - 2 * page.margin_mm);
  }() : 0;
  const double most =
      sheet > 0 ? std::min(kMostPrintSurfaceMm2, kMostPrintSheets * sheet) : kMostPrintSurfaceMm2;
  if (!(surface > most)) return;
  const Vec3 size = box.size();
  const double model_mm = scale * std::max({size.x, size.y, size.z});
  std::string message = "the model's surface at " + whole(model_mm) + " mm is " +
                        down_to_3_digits(surface / 1e6) + " m² of paper";
  if (sheet > 0)
    message += ", at least " + whole(std::ceil(surface / sheet)) + " sheets of " + options.paper;
  message += "; a print holds at most " + whole(kMostPrintSurfaceMm2 / 1e6) + " m²";
  if (sheet > 0) message += ", on at most " + whole(kMostPrintSheets) + " sheets";
  const double growth = std::sqrt(most / surface);
  const std::string on = sheet > 0 ? " on " + options.paper : "";
  if (options.scale) {
    message += ": a scale of at most " + down_to_3_digits(*options.scale * growth) +
               " mm per unit prints" + on + " (option 'scale')";
  } else {
    message += ": at most " + whole(std::floor(model_mm * growth)) + " mm prints" + on +
               " (option 'size_mm')";
  }
  if (sheet > 0 && kMostPrintSheets * sheet < kMostPrintSurfaceMm2) message += ", or larger paper";
  throw InvalidOptionException("print_too_large", options.scale ? "scale" : "size_mm", message);
}

double parts_print_scale(const std::vector<Mesh>& parts, const JobOptions& options) {
  Mesh all;
  for (const Mesh& part : parts)
    all.vertices.insert(all.vertices.end(), part.vertices.begin(), part.vertices.end());
  return print_scale(all, print_options(options));
}

std::size_t buildable_faces(const Mesh& part, double scale) {
  const double face_mm2 = std::sqrt(3.0) / 4 * kBuildableEdgeMm * kBuildableEdgeMm;
  const double faces = std::ceil(area(part) * scale * scale / face_mm2);
  return std::max<std::size_t>(
      kMinDetailFaces, std::isfinite(faces) ? static_cast<std::size_t>(std::min(faces, 1e12)) : 0);
}

SimplifyTarget detail_target(const Mesh& part, const JobOptions& options, double scale,
                             std::size_t all_faces) {
  SimplifyTarget target;
  switch (options.detail.mode) {
    case DetailMode::Full:
      return target;
    case DetailMode::Faces: {
      const double share = all_faces == 0 ? 1.0 : double(part.faces.size()) / double(all_faces);
      target.faces = std::max<std::size_t>(
          4, static_cast<std::size_t>(std::llround(share * double(options.detail.faces))));
      return target;
    }
    case DetailMode::Auto:
      break;
  }
  const std::size_t buildable = buildable_faces(part, scale);
  if (double(part.faces.size()) > kDetailSlack * double(buildable)) target.faces = buildable;
  if (scale > 0 && std::isfinite(scale)) {
    target.short_edge = kShortEdgeMm / scale;
    target.short_edges_allowed = kShortEdgesAllowed;
    target.max_distance = kDetailDistanceMm / scale;
    target.max_tunnel_loop = kTunnelLoopMm / scale;
    target.thin_face = kThinFaceMm / scale;
    target.thin_plates = true;
  }
  return target;
}

std::optional<NetRepair> leave_out_small_parts(Prepared& prepared, const JobOptions& options,
                                               double scale) {
  if (options.detail.mode != DetailMode::Auto || prepared.parts.size() < 2) return std::nullopt;
  std::vector<char> small(prepared.parts.size(), 0);
  std::size_t parts = 0, faces = 0;
  double largest_mm = 0;
  const double flat = std::cos(options.flat_fold_degrees * std::numbers::pi / 180);
  for (std::size_t p = 1; p < prepared.parts.size(); ++p) {  // the largest part stays
    const Mesh& part = prepared.parts[p];
    if (part.vertices.empty()) continue;
    const Box3 box = bounding_box(part);
    const double mm = norm(box.hi - box.lo) * scale;
    if (!(mm < kSmallestPartMm) || !folds(part, flat)) continue;
    small[p] = 1;
    ++parts;
    faces += part.faces.size();
    largest_mm = std::max(largest_mm, mm);
  }
  if (parts == 0) return std::nullopt;
  const std::size_t all = prepared.parts.size();
  std::vector<Mesh> kept;
  std::vector<MeshColour> kept_colours;
  for (std::size_t p = 0; p < all; ++p) {
    if (small[p]) continue;
    kept.push_back(std::move(prepared.parts[p]));
    if (p < prepared.part_colours.size())
      kept_colours.push_back(std::move(prepared.part_colours[p]));
  }
  prepared.parts = std::move(kept);
  prepared.part_colours = std::move(kept_colours);
  char largest[32];
  std::snprintf(largest, sizeof largest, "%.1f", largest_mm);
  return NetRepair{"small_parts_left_out", parts,
                   "left out " + std::to_string(parts) + " of " + std::to_string(all) + " parts (" +
                       std::to_string(faces) + " faces) with folds, each under " +
                       std::to_string(int(kSmallestPartMm)) +
                       " mm across at this size (the largest " + largest +
                       " mm): too small to fold and glue in card; detail full keeps them, or "
                       "print larger"};
}

std::optional<NetRepair> detail_warning(const std::vector<Piece>& pieces,
                                        const std::vector<Mesh>& parts, const JobOptions& options,
                                        double scale) {
  if (options.detail.mode == DetailMode::Auto) return std::nullopt;
  std::size_t dense = 0, faces = 0, buildable = 0;
  for (std::size_t p = 0; p < pieces.size() && p < parts.size(); ++p) {
    const std::size_t b = buildable_faces(parts[p], scale);
    if (double(pieces[p].mesh.faces.size()) <= kDetailSlack * double(b)) continue;
    ++dense;
    faces += pieces[p].mesh.faces.size();
    buildable += b;
  }
  if (dense == 0) return std::nullopt;
  return NetRepair{"detail_unbuildable", dense,
                   std::to_string(faces) + " faces printed where a person can build about " +
                       std::to_string(buildable) + " at this size (faces with edges under " +
                       std::to_string(int(kBuildableEdgeMm)) +
                       " mm: labels too small to read, edges without room for glue tabs); "
                       "detail auto collapses to that, or print larger"};
}

}  // namespace papernet::engine_detail
