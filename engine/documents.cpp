// The pipeline's last steps: the pieces as one net document, and the documents made from it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "core/io/write_mesh.h"
#include "core/mesh/mesh.h"
#include "core/unfold/net_metrics.h"
#include "engine/internal/colour.h"
#include "engine/internal/colour_pace.h"
#include "engine/internal/fit_search.h"
#include "engine/internal/run_progress.h"
#include "engine/internal/steps.h"
#include "print/arrange.h"
#include "print/build_order.h"
#include "print/colour.h"
#include "print/fit.h"
#include "print/overview.h"
#include "print/pages.h"
#include "print/pdf.h"
#include "print/placements.h"
#include "print/svg.h"

namespace papernet::engine_detail {
namespace {

// Millimetres between pieces set side by side: room for a glue tab on each, and a cut between.
double piece_gap_mm(const JobOptions& options) { return 2 * options.tab_height_mm + 4; }

// The colour resolution of the whole net's SVG beside paged prints (a preview), dots per inch.
constexpr double kPreviewDpi = 96;

// The seconds a page's colour takes per pixel of its printable area until the pages' own are
// measured (ColourPace), times the machine's slowness, for pages written into one document:
// drawing the Duck's pages in colour at 300 dpi and writing them into the PDF took 30 ns on A0
// paper (4.0 s a page) and 34 ns on A4 (0.25 s), on a machine whose slowness was 1.2
// (2026-12-06); into the PDF and the SVG pages, 57 ns on A0 (7.7 s a page).
constexpr double kColourSecondsPerPixel = 28e-9;

// The same for one drawing of the whole net (without paper, or the preview beside the pages),
// which cannot measure its pace before it is done: per pixel of its pieces' images and per
// triangle of colour, times the machine's slowness. Measured 2026-12-06 without paper: the milk
// truck at 1,000 mm, 252,000 triangles, 39.5 million pixels at 50 dpi 5.7 s and 74.3 million at
// 100 dpi 8.7 s (slowness 1.2-1.3: about 70 ns a pixel, 7 us a triangle); the truck at 200 mm at
// 300 dpi 3.7 s (42 million pixels, 78,000 triangles); the Duck at 300 dpi 3.2 s (43 million,
// slowness 1.65); the Menger sponge of level 3 at 82 dpi 13 s (60 million pixels, up to 250,000
// triangles, slowness 1.23), more than these allow for.
constexpr double kDrawingSecondsPerPixel = 90e-9;
constexpr double kDrawingSecondsPerTriangle = 10e-6;

// A piece's colour: its part's, when the piece folds into the part's own faces (possibly in
// another order: each face is found by its vertices in the same turn). A coarser mesh has
// faces of its own, without colour data; std::nullopt then.
std::optional<MeshColour> piece_colour(const Piece& piece, const Mesh& part,
                                       const MeshColour& colour) {
  if (piece.mesh.faces == part.faces && piece.mesh.vertices.size() == part.vertices.size())
    return colour;
  if (piece.mesh.faces.size() != part.faces.size() || piece.mesh.vertices != part.vertices)
    return std::nullopt;
  std::map<std::array<int, 3>, int> corner_of;  // a face's vertices from each corner -> corner
  for (std::size_t f = 0; f < part.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto& t = part.faces[f];
      corner_of[{t[k], t[(k + 1) % 3], t[(k + 2) % 3]}] = 3 * int(f) + k;
    }
  std::vector<std::array<int, 3>> corners(piece.mesh.faces.size());
  for (std::size_t f = 0; f < corners.size(); ++f) {
    const auto it = corner_of.find(piece.mesh.faces[f]);
    if (it == corner_of.end()) return std::nullopt;
    const int face = it->second / 3, k = it->second % 3;
    corners[f] = {3 * face + k, 3 * face + (k + 1) % 3, 3 * face + (k + 2) % 3};
  }
  return remap_corners(colour, corners);
}

/// The net document as printed: with layout fit its pieces are those cut to fit a sheet (each
/// naming the part it was cut from, whose result and distance it inherits); then where each
/// piece lies on the pages.
void describe_print(NetDocument& doc, const FitPieces& pieces, const PrintLayout& layout,
                    const PageLayout& pages, const PageOptions& page, bool fit) {
  if (fit) {
    std::vector<NetPiece> printed(static_cast<std::size_t>(pieces.pieces));
    for (std::size_t f = 0; f < pieces.piece.size(); ++f)
      printed[pieces.piece[f]] = doc.pieces[doc.piece[f]];
    for (NetPiece& p : printed) p.faces = 0;
    for (int p : pieces.piece) ++printed[p].faces;
    doc.pieces = std::move(printed);
    doc.piece = pieces.piece;
    doc.net = pieces.net;
  }
  NetPrint& print = doc.print.emplace();
  print.paper = page.paper.name;
  print.page_width_mm = pages.width;
  print.page_height_mm = pages.height;
  print.margin_mm = pages.margin;
  print.mm_per_unit = layout.scale;
  print.pages = static_cast<int>(pages.pages.size());
  print.layout = std::string(page_layout_name(fit ? PageLayoutMode::Fit : PageLayoutMode::Tile));
  print.title = pages.title;
  PiecePlacements placed = place_pieces(doc.net, doc.piece, layout, pages);
  print.placements = std::move(placed.pieces);
  print.tiles = std::move(placed.tiles);
  for (int k = 0; k < print.pages; ++k)
    if (pages.pages[k].overview) {
      if (print.overview_page < 0) print.overview_page = k;
      ++print.overview_pages;
    }
}

}  // namespace

NetDocument assemble(const std::vector<Piece>& pieces, const Prepared& input,
                     const JobOptions& options) {
  NetDocument doc;
  doc.strategy = strategy_name(options.strategy);
  doc.input = input.input;
  doc.repairs = input.repairs;
  doc.colour.materials = input.colour.materials;
  doc.colour.textures = input.colour.textures;
  std::size_t vertex_coloured = 0, uncoloured = 0;
  std::optional<std::vector<std::optional<Image>>> images;  // decoded when first needed
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const Piece& piece = pieces[p];
    if (p < input.part_colours.size()) {
      std::optional<MeshColour> colour = piece_colour(piece, input.parts[p], input.part_colours[p]);
      // An approximate piece of a coloured part: colours at its corners, when the part has a
      // material or vertex colours to take them from (texture coordinates alone have none).
      const MeshColour& part_colour = input.part_colours[p];
      const bool has_colour =
          !part_colour.colours.empty() ||
          std::any_of(part_colour.face_materials.begin(), part_colour.face_materials.end(),
                      [&](int m) { return m >= 0; });
      if (!colour && has_colour) {
        if (!images) images = decode_textures(input.colour);
        colour = corner_colours(piece.mesh, input.parts[p], part_colour, input.colour, *images);
        ++vertex_coloured;
      } else if (!colour) {
        ++uncoloured;
      }
      // Without: the same kinds of data, all NaN / -1 (no corner of the input maps there).
      const std::vector<std::array<int, 3>> none(piece.mesh.faces.size(),
                                                 {kNoCorner, kNoCorner, kNoCorner});
      append_faces(doc.colour, doc.mesh.faces.size(),
                   colour ? *colour : remap_corners(input.part_colours[p], none),
                   piece.mesh.faces.size());
    }
    const int vertex_base = static_cast<int>(doc.mesh.vertices.size());
    const int face_base = static_cast<int>(doc.mesh.faces.size());
    // One piece of the document per tree of the net (several when grown).
    const int piece_base = static_cast<int>(doc.pieces.size());
    const std::size_t trees = piece.grown ? piece.grown->pieces : 1;
    for (std::size_t t = 0; t < trees; ++t)
      doc.pieces.push_back({p, piece.complete ? "complete" : "approximate", 0, piece.hausdorff});
    doc.mesh.vertices.insert(doc.mesh.vertices.end(), piece.mesh.vertices.begin(),
                             piece.mesh.vertices.end());
    for (std::size_t f = 0; f < piece.mesh.faces.size(); ++f) {
      const auto& t = piece.mesh.faces[f];
      doc.mesh.faces.push_back({t[0] + vertex_base, t[1] + vertex_base, t[2] + vertex_base});
      const int parent = piece.net.parent[f];
      doc.net.parent.push_back(parent < 0 ? -1 : parent + face_base);
      doc.net.points.push_back(piece.net.points[f]);
      const int tree = piece_base + (piece.grown ? piece.grown->piece[f] : 0);
      doc.piece.push_back(tree);
      ++doc.pieces[static_cast<std::size_t>(tree)].faces;
    }
    if (!piece.complete) doc.result = "approximate";
    doc.metrics.hausdorff = std::max(doc.metrics.hausdorff, piece.hausdorff);
  }
  if (uncoloured > 0)
    doc.repairs.push_back(
        {"approximate_pieces_uncoloured", uncoloured,
         uncoloured == 1 ? std::string("1 approximate piece folds into a coarser mesh whose faces "
                                       "carry no texture coordinates or colours (null in mesh.uvs)")
                         : std::to_string(uncoloured) +
                               " approximate pieces fold into coarser meshes whose faces carry no "
                               "texture coordinates or colours (null in mesh.uvs)"});
  if (vertex_coloured > 0)
    doc.repairs.push_back(
        {"approximate_pieces_vertex_coloured", vertex_coloured,
         (vertex_coloured == 1
              ? std::string("1 approximate piece folds into a coarser mesh whose faces")
              : std::to_string(vertex_coloured) +
                    " approximate pieces fold into coarser meshes whose faces") +
             " carry vertex colours, the model's colour nearest each corner, and no texture "
             "coordinates (mesh.colors; mesh.uvs null); the print bakes the colour finer"});
  // Coverage and aspect ratio of the pieces as the print sets them side by side.
  const double gap = piece_gap_mm(options) / print_scale(doc.mesh, print_options(options));
  const NetBoxMetrics box = net_metrics(doc.mesh, arrange_pieces(doc.net, doc.piece, gap));
  doc.metrics.faces = doc.mesh.faces.size();
  doc.metrics.coverage = box.coverage;
  doc.metrics.aspect_ratio = box.aspect_ratio;
  return doc;
}

namespace {

// The warning that `labels.illegible` labels print under the legible size (docs/print.md,
// "Labels"): what is left after moving them onto tabs, over folds and away on their piece.
NetRepair small_labels_warning(const LabelSizes& labels, DetailMode detail) {
  char sizes[96];  // the smallest 0.05 mm, 4e-06 mm
  std::snprintf(sizes, sizeof sizes,
                labels.smallest_mm >= 0.01 ? "under %.1f mm (the smallest %.2f mm)"
                                           : "under %.1f mm (the smallest %.2g mm)",
                kLegibleLabelMm, labels.smallest_mm);
  std::string message = std::to_string(labels.illegible) + " of " + std::to_string(labels.count) +
                        " labels print " + sizes + ", too small to read without a magnifier: ";
  message += detail == DetailMode::Auto
                 ? "short cut edges crowded where no larger place was found; print larger"
                 : "short edges kept by the detail asked; detail auto collapses them, or print "
                   "larger";
  return NetRepair{"small_labels", labels.illegible, std::move(message)};
}

// The warning that every face prints as a piece of its own because no two faces joined by a fold
// fit a sheet together at this size (a low-poly model printed large: trimesh's BoxTextured cube
// at 200 mm on A4, 12 pieces on 12 sheets), with the size at which they do (docs/print.md, "Fit
// layout"); none otherwise.
std::optional<NetRepair> faces_apart_warning(const FitSearchOptions& search, const NetDocument& net,
                                             const FitPieces& pieces) {
  if (pieces.pieces < 2 || static_cast<std::size_t>(pieces.pieces) != net.mesh.faces.size())
    return std::nullopt;
  const double size = std::floor(
      largest_size_joining_faces(net.net, search.scale, search.room.room, search.model_mm));
  if (!(size >= 1 && size < search.model_mm)) return std::nullopt;
  char message[320];
  std::snprintf(
      message, sizeof message,
      "every face prints as a piece of its own: no two faces joined by a fold fit %s "
      "paper together, with room for their glue tabs, at %.0f mm (size_mm); at %.0f mm or "
      "less they do, in fewer, larger pieces",
      search.page.paper.name.c_str(), search.model_mm, size);
  return NetRepair{"faces_apart", net.mesh.faces.size(), message};
}

}  // namespace

FitSearchOptions fit_search_options(const JobOptions& options, const Mesh& mesh) {
  FitSearchOptions search;
  search.print = print_options(options);
  search.page = page_options(options);
  search.page.validate();
  search.tabs = tab_clearance_options(mesh, search.print);
  search.scale = print_scale(mesh, search.print);
  search.gap = piece_gap_mm(options) / search.scale;
  const Vec3 extent = bounding_box(mesh).size();
  search.model_mm = search.scale * std::max({extent.x, extent.y, extent.z});
  search.labels_count = options.detail.mode == DetailMode::Auto;
  // Tabs stick out by up to their height on each side; then the paper to cut along, and 3 mm to
  // spare for the nesting grid's cells (print/nest.h). A face too large for that prints alone,
  // its tabs on the faces beside it where they can (print/fit.h, FitRoom).
  const PageOptions& page = search.page;
  const double nest_room = kCutSpacingMm + 3;
  const double tab_room = 2 * std::max(0.0, options.tab_height_mm);
  const Vec2 alone{page.paper.width - 2 * page.margin_mm - nest_room,
                   page.paper.height - 2 * page.margin_mm - nest_room};
  const Vec2 room{alone.x - tab_room, alone.y - tab_room};
  if (!(room.x > 0 && room.y > 0))
    throw InvalidOptionException("option_out_of_range", "margin_mm",
                                 "the margins and tabs leave no room on the paper");
  search.room = {room, alone};
  search.may_tile = !options.layout.has_value();
  return search;
}

namespace {

// The print's documents (docs/print.md), `outcome.print` and their progress; with paper, the
// net document as printed (describe_print), within `seconds` where it can. A fit layout tries
// the ways of kFitWays in turn, `search_threads` at a time, while half of them last (at least
// the first), and keeps the cheapest (FitSearch); the pages are drawn in the rest (ColourPace).
void write_print(const JobOptions& options, const DocumentRequest& request, UnfoldOutcome& outcome,
                 double seconds, Progress& progress, int search_threads) {
  const auto deadline =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(std::isfinite(seconds) ? std::max(seconds, 0.0) : 1e9));
  const double search_seconds = 0.5 * seconds;
  const Mesh& mesh = outcome.net.mesh;
  Documents& docs = outcome.documents;
  const PrintOptions print = print_options(options);
  const double scale = print_scale(mesh, print);
  const double gap = piece_gap_mm(options) / scale;
  const PageOptions page = page_options(options);
  // The print path (docs/print.md): pieces, cut to fit a sheet with room for their tabs; tabs,
  // strips and labels; then nesting onto sheets (fit) or tiling (tile); then drawing.
  bool fit = has_paper(options) && options.layout != PageLayoutMode::Tile;
  std::optional<FitPrint> chosen;
  std::optional<FitSearchOptions> search;
  std::string layout_note;
  if (fit) {
    search = fit_search_options(options, mesh);
    search->seconds = search_seconds;
    search->threads = search_threads;
    FitChoice choice = search_fit(outcome.net, mesh, *search, progress);
    chosen = std::move(choice.print);
    if (!chosen) {
      fit = false;
      layout_note = choice.tiled_because + "; tiled across pages instead (layout tile)";
    }
  }
  FitPieces pieces{outcome.net.net, outcome.net.piece, 0, 0, {}};
  PieceGraph graph;
  PrintLayout layout;
  PageLayout pages;
  std::optional<PrintLayout> unpaged;  // without paper: the net as laid out, before paginate
  if (fit) {
    pieces = std::move(chosen->pieces);
    graph = std::move(chosen->graph);
    layout = std::move(chosen->layout);
    pages = std::move(chosen->pages);
  } else {
    layout = layout_net(mesh, arrange_pieces(pieces.net, pieces.piece, gap), print, pieces.piece);
    report(progress, "layout", 0.5);
    // Without paper, the SVG is the net as laid out; paginating may turn it and move strips.
    if (request.svg_pages && !has_paper(options)) unpaged = layout;
    pages = paginate(layout, page);
  }
  report(progress, "layout", 1);
  pages.title = options.title;
  // Colour (docs/colour.md, "Printing"): rasterised page by page as the pages are drawn.
  std::optional<PrintColour> colour;
  if (options.colour && !outcome.net.colour.empty()) {
    std::vector<PrintNote> notes;
    colour = print_colour(outcome.net.colour, mesh.faces.size(), options.dpi, notes);
    for (const PrintNote& note : notes)
      outcome.net.warnings.push_back({note.code, note.count, note.message});
    // Faces of approximate pieces: from the input surface nearest them (engine/colour.cpp).
    colour->faces.resize(mesh.faces.size());
    for (std::size_t f = 0; f < outcome.baked_colour.size() && f < mesh.faces.size(); ++f)
      if (!outcome.baked_colour[f].empty()) colour->faces[f] = std::move(outcome.baked_colour[f]);
    outcome.baked_colour.clear();
    if (!colour->any()) colour.reset();
  }
  const PrintColour* paint = colour ? &*colour : nullptr;
  PrintSummary& summary = outcome.print.emplace();
  summary.cut_edges = static_cast<std::size_t>(layout.cut_edges);
  summary.tabs = layout.tabs.size();
  summary.strips = layout.strips.size();
  summary.tabs_omitted = layout.omitted_tabs.size();
  const LabelSizes labels = label_sizes(layout);
  summary.labels = labels.count;
  summary.smallest_label_mm = labels.smallest_mm;
  summary.small_labels = labels.illegible;
  if (labels.illegible > 0)
    outcome.net.warnings.push_back(small_labels_warning(labels, options.detail.mode));
  if (fit)
    if (std::optional<NetRepair> apart = faces_apart_warning(*search, outcome.net, pieces))
      outcome.net.warnings.push_back(std::move(*apart));
  if (fit && options.overview.value_or(pieces.pieces > 1)) {
    summary.overview = add_overview(pages, layout, pieces.piece, std::move(graph), mesh,
                                    view_axes(outcome.format), options.colour);
    for (const Page& p : pages.pages) summary.overview_pages += p.overview ? 1 : 0;
    if (!summary.overview) {
      char area[64];
      std::snprintf(area, sizeof area, "%.0f x %.0f mm", page.paper.width - 2 * page.margin_mm,
                    page.paper.height - 2 * page.margin_mm);
      outcome.net.warnings.push_back({"overview_left_out", 1,
                                      "the overview page is left out: " + page.paper.name +
                                          " paper within its margins (" + area +
                                          ") is too small for it"});
    }
  }
  // Seconds left of the job's time limit (infinite without one).
  const auto seconds_left = [&] {
    return std::isfinite(seconds)
               ? std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count()
               : std::numeric_limits<double>::infinity();
  };
  // The seconds one drawing of the whole net takes whatever its resolution (its triangles of
  // colour) on this machine; 0 without a time limit.
  const auto triangle_seconds = [&] {
    if (!colour || !std::isfinite(seconds)) return 0.0;
    std::size_t triangles = 0;
    for (const auto& face : colour->faces) triangles += face.size();
    return static_cast<double>(triangles) * kDrawingSecondsPerTriangle * machine_slowness();
  };
  if (unpaged) {
    // Without paper the one drawing is the print: its colour at the resolution asked, lowered to
    // what the time left draws (half of it when the PDF's pages follow) and to kMostDrawingPixels,
    // else left out, each with the pages' warning.
    const PrintColour* drawn = paint;
    if (colour) {
      const double asked = colour->dpi;
      const std::vector<double> areas = colour_image_areas(*unpaged, *colour);
      const auto pixels = [&](double dpi) { return colour_images_pixels(areas, dpi); };
      bool by_time = false;
      colour->dpi =
          drawing_dpi(asked, pixels, (request.pdf ? 0.5 : 1) * seconds_left(),
                      std::isfinite(seconds) ? kDrawingSecondsPerPixel * machine_slowness() : 0,
                      triangle_seconds(), by_time);
      const auto dpi = [](double d) { return std::to_string(static_cast<long>(d)) + " dpi"; };
      const std::string most = std::to_string(static_cast<long>(kMostDrawingPixels / 1e6));
      const std::string drawing = "the drawing of the net (paper none) prints ";
      if (colour->dpi == 0) {
        drawn = nullptr;
        outcome.net.warnings.push_back(
            {"colour_left_out", 1,
             drawing + "without its colour (line art only): even at " + dpi(kMinColourDpi) +
                 (by_time ? " it would not have been drawn within the job's time limit; a "
                            "longer time limit prints it in colour"
                          : " its colour would be more than the " + most +
                                " million pixels one drawing holds; on paper each page "
                                "holds its own")});
      } else if (colour->dpi < asked) {
        outcome.net.warnings.push_back(
            {"colour_resolution_lowered", 1,
             drawing + "its colour at " + dpi(colour->dpi) + ", lower than the " + dpi(asked) +
                 " asked" +
                 (by_time ? ", so that the job ends within its time limit; a longer time limit "
                            "prints it at a higher resolution"
                          : ": at " + dpi(asked) + " its colour would be " +
                                std::to_string(static_cast<long>(pixels(asked) / 1e6)) +
                                " million pixels, more than the " + most +
                                " million one drawing holds; on paper every page prints "
                                "at " +
                                dpi(asked))});
      }
    }
    docs.svg_pages = {write_net_svg(*unpaged, page.margin_mm, drawn, options.title)};
    if (colour) colour->dpi = options.dpi;  // the PDF's pages are paced on their own
  }
  report(progress, "write", 0);
  summary.pages = static_cast<int>(pages.pages.size());
  summary.layout = std::string(page_layout_name(fit ? PageLayoutMode::Fit : PageLayoutMode::Tile));
  summary.pieces = fit ? pieces.pieces : static_cast<int>(outcome.net.pieces.size());
  summary.cut_links = pieces.cut_links;
  summary.layout_note = std::move(layout_note);
  if (has_paper(options)) describe_print(outcome.net, pieces, layout, pages, page, fit);
  // Each page drawn (and coloured) once for the PDF and its SVG; a cancelled job, a stopping
  // node or the time limit stops between pages.
  const bool paged = has_paper(options);
  const bool svg_pages = paged && (request.svg_pages || (request.svg && pages.pages.size() == 1));
  std::optional<PdfWriter> pdf;
  if (request.pdf) pdf.emplace(layout, pages.width, pages.height, pages.title);
  const int n = static_cast<int>(pages.pages.size());
  // With colour, page i + 1 is drawn (its images rasterised) on a thread of its own while page i
  // is written (cairo compresses its images; the writing is the longer: the Duck on A0 at 300 dpi
  // 2.5 s drawing, 4 s written into the PDF, 7.7 s into the PDF and an SVG page), and at most two
  // pages' images are held. Only that thread samples the textures; the resolution changes only
  // between two drawings.
  const auto policy = paint ? std::launch::async : std::launch::deferred;
  auto draw = [&](int i, const PrintColour* with) { return draw_page(layout, pages, i, with); };
  ColourPace pace(
      deadline, colour ? colour->dpi : 0, pages,
      colour && std::isfinite(seconds) ? kColourSecondsPerPixel * machine_slowness() : 0,
      (pdf ? 1 : 0) + (svg_pages ? 1 : 0));
  const auto paint_at = [&](int i) {
    if (colour) colour->dpi = pace.next_dpi(i);
    return colour && colour->dpi > 0 ? paint : nullptr;
  };
  std::future<PageDrawing> next;
  if ((pdf || svg_pages) && n > 0) next = std::async(policy, draw, 0, paint_at(0));
  for (int i = 0; (pdf || svg_pages) && i < n; ++i) {
    if (progress.cancelled()) throw CancelledException();
    const PageDrawing drawing = next.get();
    if (i + 1 < n) next = std::async(policy, draw, i + 1, paint_at(i + 1));
    if (pdf) pdf->add_page(drawing);
    if (svg_pages) docs.svg_pages.push_back(write_page_svg(layout, drawing, i, n));
    report(progress, "write", 0.8 * (i + 1) / n);
  }
  for (NetRepair& warning : pace.warnings(n)) outcome.net.warnings.push_back(std::move(warning));
  if (pdf) docs.pdf = pdf->finish();
  if (request.svg) {
    if ((paged && n == 1) || unpaged) {
      docs.svg = docs.svg_pages.front();  // the one page, or the one drawing without paper
    } else {
      // The whole net in one SVG beside paged prints is a preview (the pages are the print): its
      // colour at screen resolution at most, lowered to what the time left draws at the pages'
      // pace, else left out (no warning: the print is as it says).
      const PrintColour* drawn = paint;
      if (colour) {
        bool by_time = false;
        const std::vector<double> areas = colour_image_areas(layout, *colour);
        colour->dpi = drawing_dpi(
            std::min(options.dpi, kPreviewDpi),
            [&](double dpi) { return colour_images_pixels(areas, dpi); }, seconds_left(),
            std::isfinite(seconds) ? std::max(pace.seconds_per_pixel_written_once(),
                                              kDrawingSecondsPerPixel * machine_slowness())
                                   : 0,
            triangle_seconds(), by_time);
        if (colour->dpi == 0) drawn = nullptr;
      }
      docs.svg = write_net_svg(layout, page.margin_mm, drawn, options.title);
    }
  }
  if (!request.svg_pages && paged) docs.svg_pages.clear();
}

}  // namespace

void write_documents(const JobOptions& options, const DocumentRequest& request,
                     UnfoldOutcome& outcome, double seconds, Progress& progress,
                     int search_threads) {
  if (request.print()) write_print(options, request, outcome, seconds, progress, search_threads);
  report(progress, "write", 0.9);
  Documents& docs = outcome.documents;
  docs.net_json = write_net_json(outcome.net);
  if (request.glb) docs.glb = write_glb(outcome.net.mesh, outcome.net.colour);
  if (request.obj) docs.obj = write_obj(outcome.net.mesh);
}

}  // namespace papernet::engine_detail
