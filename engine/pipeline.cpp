// The pipeline (docs/architecture.md): one function from a model's bytes and the job's options to
// checked nets and their documents, for the command line and the service alike. Its steps are
// in engine/internal/steps.h; this file runs them piece by piece and relays progress.
#include "engine/pipeline.h"

#include <time.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "core/errors.h"
#include "engine/internal/colour.h"
#include "engine/internal/run_progress.h"
#include "engine/internal/steps.h"
#include "print/layout.h"
#include "print/tabs.h"

namespace papernet {
namespace {

using namespace engine_detail;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Shares of the job's time limit kept from the steps before them for the tab-room pass and for
// the print (layout and drawing), when they run: the unfolder gets the rest, the pass what is
// left of the limit without the print's share, and the print what is left then. So the whole
// job ends within its limit even when the unfolder would use all of it (docs/architecture.md,
// "Time limit"). The tenths are enough for a net the unfolder reached in a tenth of the limit;
// a larger net needs the time per face below.
constexpr double kTabRoomTimeShare = 0.1;
constexpr double kPrintTimeShare = 0.1;
// Seconds per face of the net that the steps after the unfold take on a large net, measured on
// rocker-arm's nets of 18,000-20,000 faces (docs/architecture.md, "Time limit"): the print's
// layout and drawing (2.2 s for an SVG, 2.9 s for a PDF, 3.3 s for PDF, SVG and glTF), the
// tab-room pass's report, last check and overrun of its limit (0.3-0.5 s), and the distance of an
// approximate net to the input (0.2-0.3 s). The unfolder leaves them that time for the net it
// reaches, less the print's share already kept from it.
constexpr double kPrintSecondsPerFace = 175e-6;
constexpr double kTabRoomSecondsPerFace = 25e-6;
constexpr double kDistanceSecondsPerFace = 12e-6;
// Seconds the print takes for each glue strip, besides its time per face: each strip is nested
// onto the sheets as a part of its own (print/nest.h). The pass that makes room for tabs keeps
// this much of its time per edge still without room. Measured on the Twin plate of
// ../shared/data/bench (5,756 faces of slivers; docs/architecture.md, "Time limit").
constexpr double kPrintSecondsPerStrip = 3e-3;
// The colour baked onto approximate faces (engine/colour.cpp) is cut into small triangles, each
// held and filled on its own: their most (about 250 bytes each), their cost beyond the pixels they
// fill (baked, copied and filled: 1.54 million of the Menger sponge of level 3 took 4 s more than
// 49,000 did at 300 dpi, 2026-11-29), and the share of the time left after the tab-room pass that
// it may take: the layout's search takes up to half of that time, and the pages' pixels much of the
// rest.
constexpr std::size_t kMostBakedTriangles = 250'000;
constexpr double kColourSecondsPerTriangle = 3e-6;
constexpr double kColourTimeShare = 0.2;

// How much slower than the machine those times were measured on this one runs: a fixed piece of
// the print's most common work (convex polygons tested for overlap through a PolygonGrid,
// print/tabs.h), timed in the thread's CPU time (other processes' load aside) once per process,
// the median of seven runs, against kProbeSeconds, its time there. The times per face above are
// multiplied by it (never below a quarter), so that on a slower machine the unfolder leaves the
// steps after it the time they take there (docs/architecture.md, "Time limit"). Measured on
// session 43's machine: the probe 1.74 ms (the median of 12 jobs; 3 of them took 1.4-2.1 times
// as long), rocker-arm's print 282 us per face (PDF, SVG and glTF of an 11,258-face net in
// 3.18 s), 1.61 times the 175 us above; so 1.74 / 1.61 ms there.
constexpr double kProbeSeconds = 1.08e-3;
// Jobs of fewer faces do not time the machine: the time their nets need after the unfold is
// within the print's share of any time limit. Nor do jobs whose steps after the unfold take at
// most kUnprobedSeconds at the times above (a net written as JSON alone, with no tab-room pass,
// keeps only the distance's 12 us per face: 8,333 faces): were the machine even five times
// slower, the unfolder would misjudge their end by under half a second, and the probe costs
// 12 ms, a tenth of an unfold of 2,000 faces.
constexpr std::size_t kProbeFaces = 2'000;
constexpr double kUnprobedSeconds = 0.1;
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double probe_slowness() {
  static const double slowness = [] {
    constexpr int kSide = 40;  // 2 x 40 x 40 triangles
    PolygonGrid grid(1);
    for (int i = 0; i < kSide; ++i)
      for (int j = 0; j < kSide; ++j) {
        const Vec2 p{static_cast<double>(i), static_cast<double>(j)};
        grid.add(std::array{p, p + Vec2{1, 0}, p + Vec2{1, 1}});
        grid.add(std::array{p, p + Vec2{1, 1}, p + Vec2{0, 1}});
      }
    std::array<double, 7> runs{};
    std::size_t hits = 0;  // every query meets the grid; counted so that none is optimised away
    for (double& seconds : runs) {
      const double begin = thread_seconds();
      for (int round = 0; round < 8; ++round)
        for (int i = 0; i < kSide; ++i)
          for (int j = 0; j < kSide; ++j) {
            const Vec2 p{i + 0.1 * round, j + 0.05 * round};
            hits += grid.overlaps(std::array{p, p + Vec2{0.9, 0.2}, p + Vec2{0.4, 0.8}}, 1e-6);
          }
      seconds = thread_seconds() - begin;
    }
    std::nth_element(runs.begin(), runs.begin() + 3, runs.end());
    return hits > 0 ? std::max(0.25, runs[3] / kProbeSeconds) : 1;
  }();
  return slowness;
}

// An intermediate net is rendered at most this often: rendering costs time the unfolder could
// use.
constexpr auto kIntermediateInterval = std::chrono::seconds(2);

// The core algorithms' progress for one piece, forwarded to the caller's hook counted over all
// pieces; an intermediate net of the piece, with the pieces done before it, becomes an outcome
// with its documents.
class Relay : public Progress {
 public:
  Relay(RunProgress& to, const Prepared& input, const JobOptions& options,
        const DocumentRequest& documents, const std::vector<Piece>& done)
      : to_(to), input_(input), options_(options), documents_(documents), done_(done) {}
  // Starts piece `index` of `stage` within `seconds`: `faces_before` faces of the input are in
  // the pieces before it.
  void start(Stage stage, std::size_t index, std::size_t faces_before, double seconds) {
    piece_ = index;
    faces_before_ = faces_before;
    to_.start(stage, seconds, faces_before, input_.parts[index].faces.size(), all_faces());
  }
  void report(const ProgressInfo& info) override {
    ProgressInfo copy = info;
    copy.piece = piece_ + 1;
    copy.pieces = input_.parts.size();
    copy.faces = faces_before_ + info.faces;
    copy.input_faces = input_.input.faces;
    to_.report(copy);
  }
  void intermediate(const Mesh& mesh, const Net& net) override {
    if (!to_.wants_intermediates()) return;
    const auto now = Clock::now();
    if (rendered_ && now - last_ < kIntermediateInterval) return;
    rendered_ = true;
    last_ = now;
    std::vector<Piece> pieces = done_;
    pieces.push_back({mesh, net, false, false, 0, 0, {}});
    UnfoldOutcome outcome;
    outcome.format = input_.format;  // the overview's views: which way is up
    outcome.net = assemble(pieces, input_, options_);
    outcome.net.result = "approximate";
    outcome.net.intermediate = true;
    // The run's progress is the unfolder's, not this drawing's: its reports go nowhere, but a
    // cancel stops it between its pages, as it stops the run. A preview is line art (colour is
    // for the final print).
    struct Quiet : Progress {
      explicit Quiet(RunProgress& run) : run(run) {}
      bool cancelled() override { return run.cancelled(); }
      RunProgress& run;
    } quiet(to_);
    JobOptions line_art = options_;
    line_art.colour = false;
    write_documents(line_art, documents_, outcome, 0, quiet);  // one layout tried: a preview
    to_.intermediate_outcome(outcome);
  }
  bool cancelled() override { return to_.cancelled(); }

 private:
  std::size_t all_faces() const {
    std::size_t all = 0;
    for (const Mesh& part : input_.parts) all += part.faces.size();
    return all;
  }
  RunProgress& to_;
  const Prepared& input_;
  const JobOptions& options_;
  const DocumentRequest& documents_;
  const std::vector<Piece>& done_;
  std::size_t piece_ = 0, faces_before_ = 0;
  bool rendered_ = false;
  Clock::time_point last_;
};

// A share of `total` for a part of `faces` of `all` faces (a time budget).
double share(double total, std::size_t faces, std::size_t all) {
  return all == 0 ? total : total * static_cast<double>(faces) / static_cast<double>(all);
}

// The warning "unfolded_in_pieces" when a part's net is grown pieces (unfold_piece), or none:
// why for each kind of part (none found within the time limit; none there is), then how.
std::optional<NetRepair> grown_warning(const std::vector<Piece>& pieces) {
  std::size_t parts = 0, grown = 0;
  std::size_t searched = 0, searched_faces = 0, overlaps = 0, trees = 0, tree_faces = 0;
  for (const Piece& piece : pieces) {
    if (!piece.grown) continue;
    ++parts;
    grown += piece.grown->pieces;
    if (piece.grown->tree) {
      ++trees;
      tree_faces += piece.mesh.faces.size();
    } else {
      ++searched;
      searched_faces += piece.mesh.faces.size();
      overlaps += piece.grown->overlaps;
    }
  }
  if (parts == 0) return std::nullopt;
  const auto of_parts = [](std::size_t n, std::size_t faces) {
    return std::to_string(n) + (n == 1 ? " part" : " parts") + " of " + std::to_string(faces) +
           " faces";
  };
  std::string text;
  if (searched > 0)
    text = "no overlap-free net in one piece within the time limit for " +
           of_parts(searched, searched_faces) + " (the best left " + std::to_string(overlaps) +
           " overlapping face pairs)";
  if (trees > 0)
    text += (searched > 0 ? "; " : "") +
            std::string("no overlap-free net in one piece exists for ") +
            of_parts(trees, tree_faces) +
            (trees == 1 ? " (its faces join without a loop: its dual graph is a tree, and the one "
                          "edge unfolding that leaves overlaps itself)"
                        : " (their faces join without a loop: their dual graphs are trees, and the "
                          "one edge unfolding each leaves overlaps itself)");
  text += ": unfolded in " + std::to_string(grown) + " pieces grown from single faces instead";
  if (searched > 0) text += "; a longer time limit or another seed may find one piece";
  return NetRepair{"unfolded_in_pieces", parts, text};
}

// The warning for colour baked onto approximate faces in triangles larger than usual
// (bake_colour), to keep its drawing within the job's memory and time limit.
NetRepair coarser_colour_warning(double step_mm, double time_limit) {
  char step[32], usual[32], limit[32];
  std::snprintf(step, sizeof step, "%.1f", step_mm);
  std::snprintf(usual, sizeof usual, "%.1f", kBakeStepMm);
  std::snprintf(limit, sizeof limit, "%g s", time_limit);
  return NetRepair{"colour_sampled_coarser", 1,
                   "the colour of the coarser mesh's faces is sampled from the model every " +
                       std::string(step) + " mm instead of every " + usual +
                       " mm, so that drawing it keeps within the job's memory and time limit (" +
                       limit + ")"};
}

}  // namespace

double engine_detail::machine_slowness() { return probe_slowness(); }

UnfoldOutcome run_pipeline(const JobInput& input, const JobOptions& options,
                           const PipelineLimits& limits, const DocumentRequest& documents,
                           PipelineProgress& progress) {
  const auto start = Clock::now();
  const double time_limit = options.time_limit.value_or(limits.default_time_limit);
  RunPlan plan;
  plan.progressive = options.strategy != Strategy::TU;
  plan.simplify = options.detail.mode != DetailMode::Full;  // auto collapses dense parts
  plan.tabs = makes_tab_room(print_options(options));
  plan.print = documents.print();
  RunProgress tracked(progress, plan);
  // The steps after the unfolder keep their shares of the time limit (kTabRoomTimeShare, ...).
  const double print_share = plan.print ? kPrintTimeShare : 0;
  const double unfold_end = time_limit * (1 - print_share - (plan.tabs ? kTabRoomTimeShare : 0));
  tracked.start(Stage::Prepare);
  Prepared prepared = prepare(load_input(input, limits, tracked), options, tracked);
  // The model's size on paper is the whole model's, small parts included.
  const double scale = parts_print_scale(prepared.parts, options);
  if (plan.print) check_print_size(prepared.parts, options, scale);
  std::optional<NetRepair> small_parts = leave_out_small_parts(prepared, options, scale);
  // Pages in colour take most of the print's time: its drawing's part of the bar grows.
  tracked.set_colour(plan.print && options.colour &&
                     std::any_of(prepared.part_colours.begin(), prepared.part_colours.end(),
                                 [](const MeshColour& c) { return !c.empty(); }));
  std::size_t all_faces = 0;
  for (const Mesh& part : prepared.parts) all_faces += part.faces.size();
  // The time per face of the steps after the unfold, on this machine.
  const double after_at_probe_speed = (plan.print ? kPrintSecondsPerFace : 0) +
                                      (plan.tabs ? kTabRoomSecondsPerFace : 0) +
                                      kDistanceSecondsPerFace;
  const bool probe = all_faces >= kProbeFaces &&
                     after_at_probe_speed * static_cast<double>(all_faces) > kUnprobedSeconds;
  const double slowness = probe ? machine_slowness() : 1;
  const double print_per_face = plan.print ? slowness * kPrintSecondsPerFace : 0;
  const double print_per_strip = plan.print ? slowness * kPrintSecondsPerStrip : 0;
  const double tab_room_per_face = slowness * kTabRoomSecondsPerFace;
  const double after_per_face = slowness * after_at_probe_speed;

  // Each part unfolded in turn (collapsed first as `detail` says), with a share of the
  // unfolder's time left as large as its share of the faces left.
  UnfoldOutcome out;
  out.format = prepared.format;
  std::vector<Piece> pieces;
  Relay relay(tracked, prepared, options, documents, pieces);
  std::size_t faces_before = 0;
  for (std::size_t p = 0; p < prepared.parts.size(); ++p) {
    const Mesh& part = prepared.parts[p];
    const double left = std::max(unfold_end - seconds_since(start), 0.0);
    const double seconds =
        std::max(share(left, part.faces.size(), all_faces - faces_before), kLeastSeconds);
    relay.start(Stage::Unfold, p, faces_before, seconds);
    const SimplifyTarget detail = detail_target(part, options, scale, all_faces);
    // The print's share of the part is outside its seconds already.
    const AfterUnfold after{after_per_face,
                            share(time_limit * print_share, part.faces.size(), all_faces)};
    pieces.push_back(unfold_piece(part, options, detail, seconds, after, part.faces.size(), relay));
    out.simplified |= pieces.back().simplified;
    out.iterations += pieces.back().iterations;
    faces_before += part.faces.size();
  }
  const double seconds = seconds_since(start);

  // The pass that makes room for tabs gets what is left of the time limit without the print's
  // share, or its time for the faces of the nets when that is more, shared the same way, less
  // its report's time; none left, it does not run.
  std::size_t net_faces = 0;
  for (const Piece& piece : pieces) net_faces += piece.mesh.faces.size();
  const double print_end = time_limit - std::max(time_limit * print_share,
                                                 print_per_face * static_cast<double>(net_faces));
  const double left = print_end - seconds_since(start);
  faces_before = 0;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const double piece_seconds =
        share(left, prepared.parts[p].faces.size(), all_faces) -
        tab_room_per_face * static_cast<double>(pieces[p].mesh.faces.size());
    relay.start(Stage::Tabs, p, faces_before, piece_seconds);
    const bool room = plan.tabs && piece_seconds > 0 && !pieces[p].grown;
    if (room) {
      ProgressInfo info;
      info.phase = "tabs";  // changing cuts so that glue tabs fit (docs/tabs.md, stage 0)
      info.faces = pieces[p].mesh.faces.size();
      relay.report(info);
    }
    const NetCheckReport check = room ? make_room_for_tabs(pieces[p], options, piece_seconds,
                                                           print_per_strip, relay, out.tab_room)
                                      : check_piece(pieces[p]);
    if (!check.ok()) throw std::logic_error("the net fails the net checker: " + check.summary());
    faces_before += prepared.parts[p].faces.size();
  }

  tracked.start(Stage::Print, std::max(time_limit - seconds_since(start), kLeastSeconds));
  ProgressInfo info;
  info.phase = plan.print ? "layout" : "write";
  info.faces = faces_before;
  info.input_faces = prepared.input.faces;
  tracked.report(info);
  out.net = assemble(pieces, prepared, options);
  out.net.detail = {
      options.detail.mode == DetailMode::Faces ? "faces" : detail_name(options.detail),
      out.net.mesh.faces.size()};
  if (auto warning = detail_warning(pieces, prepared.parts, options, scale))
    out.net.warnings.push_back(std::move(*warning));
  if (small_parts) out.net.warnings.push_back(std::move(*small_parts));
  if (auto warning = grown_warning(pieces)) out.net.warnings.push_back(std::move(*warning));
  out.net.metrics.seconds = seconds;
  if (options.colour && documents.print()) {
    // The baked colour keeps within its memory and its share of the time left (the side of its
    // small triangles grows), where a net of many approximate faces would take minutes and a
    // gigabyte (the Menger sponge of level 3: 1.54 million triangles).
    const double left = std::max(time_limit - seconds_since(start), 0.0);
    const double most = kColourTimeShare * left / (slowness * kColourSecondsPerTriangle);
    BakedColour baked = bake_colour(
        pieces, prepared, scale,
        static_cast<std::size_t>(std::min(most, static_cast<double>(kMostBakedTriangles))));
    if (baked.coarser)
      out.net.warnings.push_back(coarser_colour_warning(baked.step_mm, time_limit));
    out.baked_colour = std::move(baked.faces);
  }
  // The print gets what is left: half of it the layout's search for fewer sheets.
  write_documents(options, documents, out, time_limit - seconds_since(start), tracked);
  tracked.finish(out.net.mesh.faces.size(), prepared.input.faces);
  return out;
}

}  // namespace papernet
