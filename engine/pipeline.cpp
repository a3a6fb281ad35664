// The pipeline (docs/architecture.md): one function from a model's bytes and the job's options to
// a checked net and its documents, for the command line and the service alike.
#include "engine/pipeline.h"

#include <algorithm>
#include <chrono>
#include <numbers>
#include <utility>

#include "core/errors.h"
#include "core/io/write_mesh.h"
#include "core/mesh/hausdorff.h"
#include "core/mesh/simplify.h"
#include "core/mesh/validate.h"
#include "core/tabs/tab_clearance_report.h"
#include "core/unfold/net_check.h"
#include "core/unfold/net_metrics.h"
#include "core/unfold/progressive.h"
#include "core/unfold/tabu.h"
#include "print/pages.h"
#include "print/pdf.h"
#include "print/svg.h"

namespace papernet {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Seconds the tab-room pass gets even when the unfolder used the job's whole time limit (the
// service's grace beyond the limit covers it and the documents).
constexpr double kMinTabRoomSeconds = 1;

// The tab room report's threshold for a flat vertex (angle defect); only its flat-leaf counts
// depend on it, and those are not reported.
constexpr double kFlatDefect = 10 * std::numbers::pi / 180;

// An intermediate net is rendered at most this often: rendering costs time the unfolder could
// use.
constexpr auto kIntermediateInterval = std::chrono::seconds(2);

struct Validated {
  Mesh mesh;
  NetInput input;
};

// Loads and validates; what cannot be unfolded fails here with the validator's report.
Validated load_and_validate(const JobInput& job, const JobOptions& options,
                            const PipelineLimits& limits, Progress& progress) {
  LoadOptions load_options;
  load_options.max_bytes = limits.max_bytes;
  // A count over the limit is refused by the loader before it allocates.
  load_options.max_faces = limits.max_faces;
  load_options.external_files = job.external_files;
  ProgressInfo info;
  info.phase = "load";
  progress.report(info);
  LoadedMesh loaded = load_mesh(job.mesh, job.format, load_options);
  info.input_faces = loaded.mesh.faces.size();
  info.faces = info.input_faces;
  info.phase = "validate";
  progress.report(info);
  if (loaded.mesh.faces.size() > limits.max_faces)
    throw LimitExceededException(LimitExceededException::Limit::Faces,
                                 "the mesh has " + std::to_string(loaded.mesh.faces.size()) +
                                     " faces; at most " + std::to_string(limits.max_faces) +
                                     " are unfolded here");
  ValidateOptions validate_options;
  validate_options.keep_largest_component = options.keep_largest_component;
  ValidationReport report = validate(loaded, validate_options);
  if (!report.unfoldable()) throw InvalidMeshException(std::move(report));
  if (progress.cancelled()) throw CancelledException();
  Validated out;
  out.input.vertices = report.vertices;
  out.input.faces = report.faces;
  out.input.genus = static_cast<int>(report.genus);
  out.input.boundaries = report.boundary_loops;
  out.mesh = options.keep_largest_component && !report.largest_component.faces.empty()
                 ? std::move(report.largest_component)
                 : std::move(loaded.mesh);
  return out;
}

// The documents of one net; fills `outcome.print` when a print document is asked for.
void write_documents(const JobOptions& options, const DocumentRequest& request,
                     UnfoldOutcome& outcome) {
  const Mesh& mesh = outcome.net.mesh;
  Documents& docs = outcome.documents;
  docs.net_json = write_net_json(outcome.net);
  if (request.glb) docs.glb = write_glb(mesh);
  if (request.obj) docs.obj = write_obj(mesh);
  if (!request.print()) return;
  PrintLayout layout = layout_net(mesh, outcome.net.net, print_options(options));
  const PageOptions page = page_options(options);
  PrintSummary& print = outcome.print.emplace();
  print.cut_edges = static_cast<std::size_t>(layout.cut_edges);
  print.tabs = layout.tabs.size();
  print.strips = layout.strips.size();
  print.tabs_omitted = layout.omitted_tabs.size();
  // Without paper, the SVG is the net as laid out; paginating may turn it and move strips.
  if (request.svg_pages && !has_paper(options))
    docs.svg_pages = {write_net_svg(layout, page.margin_mm)};
  const PageLayout pages = paginate(layout, page);
  print.pages = static_cast<int>(pages.pages.size());
  if (request.pdf) docs.pdf = write_pdf(layout, pages);
  if (request.svg_pages && has_paper(options)) docs.svg_pages = write_page_svgs(layout, pages);
  if (request.svg)
    docs.svg = has_paper(options) && pages.pages.size() == 1
                   ? write_page_svgs(layout, pages).front()
                   : write_net_svg(layout, page.margin_mm);
}

// The core algorithms' progress, forwarded to the caller's hook; intermediate nets become
// outcomes with their documents.
class Relay : public Progress {
 public:
  Relay(PipelineProgress& to, const NetInput& input, const JobOptions& options,
        const DocumentRequest& documents)
      : to_(to), input_(input), options_(options), documents_(documents) {}
  void report(const ProgressInfo& info) override {
    ProgressInfo copy = info;
    if (copy.input_faces == 0) copy.input_faces = input_.faces;
    to_.report(copy);
  }
  void intermediate(const Mesh& mesh, const Net& net) override {
    if (!to_.wants_intermediates()) return;
    const auto now = Clock::now();
    if (rendered_ && now - last_ < kIntermediateInterval) return;
    rendered_ = true;
    last_ = now;
    UnfoldOutcome outcome;
    outcome.net.result = "approximate";
    outcome.net.strategy = strategy_name(options_.strategy);
    outcome.net.input = input_;
    outcome.net.mesh = mesh;
    outcome.net.net = net;
    outcome.net.intermediate = true;
    const NetBoxMetrics box = net_metrics(mesh, net);
    outcome.net.metrics.faces = mesh.faces.size();
    outcome.net.metrics.coverage = box.coverage;
    outcome.net.metrics.aspect_ratio = box.aspect_ratio;
    write_documents(options_, documents_, outcome);
    to_.intermediate_outcome(outcome);
  }
  bool cancelled() override { return to_.cancelled(); }

 private:
  PipelineProgress& to_;
  const NetInput& input_;
  const JobOptions& options_;
  const DocumentRequest& documents_;
  bool rendered_ = false;
  Clock::time_point last_;
};

// The net of the job's strategy: plain Tabu Unfolding (TU) or progressive unfolding.
struct Unfolded {
  Mesh mesh;  // what the net folds into (a coarser mesh when approximate)
  Net net;
  bool complete = true;
  double hausdorff = 0;
  std::size_t iterations = 0;
};

// The collapses of a progressive strategy (AUTO's are QQ's), and those that simplify uses for TU.
CollapseStrategy collapses_of(Strategy strategy) {
  switch (strategy) {
    case Strategy::SEMP:
      return CollapseStrategy::SEMP;
    case Strategy::SEQ:
      return CollapseStrategy::SEQ;
    case Strategy::QQ:
    case Strategy::TU:
    case Strategy::AUTO:
      break;
  }
  return CollapseStrategy::QQ;
}

Unfolded unfold_mesh(const Mesh& mesh, const NetInput& input, const JobOptions& options,
                     double time_limit, Progress& progress) {
  TabuOptions tabu;
  tabu.seed = options.seed;
  tabu.time_limit_seconds = time_limit;
  tabu.input_faces = input.faces;
  if (options.strategy == Strategy::TU) {
    UnfoldResult r = unfold_tabu(mesh, tabu, progress);
    if (!r.overlap_free)
      throw UnfoldFailedException(r.overlaps, r.stats.iterations, mesh.faces.size(), input.faces);
    return {mesh, std::move(r.net), true, 0, r.stats.iterations};
  }
  ProgressiveOptions p;
  p.strategy = collapses_of(options.strategy);
  p.target_faces = options.target_faces.value_or(0);
  p.tabu = tabu;
  p.complete_first = options.strategy == Strategy::AUTO;
  ProgressiveResult r = unfold_progressive(mesh, p, progress);
  if (!r.overlap_free)
    throw UnfoldFailedException(r.overlaps, r.stats.iterations, r.mesh.faces.size(), input.faces);
  return {std::move(r.mesh), std::move(r.net), r.complete, r.hausdorff, r.stats.iterations};
}

// Changes the cuts so that more cut edges have room for a glue tab at the print's size (when the
// job prints tabs), keeping the new net only when it passes the net checker. Returns the
// checker's report on the net it leaves.
NetCheckReport make_room_for_tabs(const Mesh& mesh, Net& net, const JobOptions& options,
                                  double seconds, Progress& progress,
                                  std::optional<TabRoomSummary>& summary) {
  PrintOptions print = print_options(options);
  if (!makes_tab_room(print)) return check_net(mesh, net);
  ProgressInfo info;
  info.phase = "tabs";
  info.faces = mesh.faces.size();
  progress.report(info);
  print.tab_room_seconds = seconds;
  const TabClearanceOptions clearance = tab_clearance_options(mesh, print);
  const auto start = Clock::now();
  const TabClearanceResult room = clear_tab_room(mesh, net, clearance, progress);
  TabRoomSummary& s = summary.emplace();
  s.seconds = seconds_since(start);
  s.blocked_before = room.blocked_before;
  s.blocked_after = room.blocked_after;
  s.moves = room.moves;
  s.kicks = room.kicks;
  s.evaluations = room.evaluations;
  std::optional<NetCheckReport> report;
  if (room.moves > 0) {
    report = check_net(mesh, room.net);
    if (report->ok()) {
      net = room.net;
    } else {
      s.rejected = true;
      s.blocked_after = s.blocked_before;
      report.reset();
    }
  }
  if (s.blocked_after > 0) {
    // Why edges stay without room: a leaf of the cut tree at a nearly flat vertex always lacks
    // it, and a dense mesh has few vertices where a leaf can have it.
    const TabRoomReport why = describe_tab_room(mesh, net, clearance, kFlatDefect);
    s.leaves_without_room = why.leaves_without_room_blocked;
    s.leaf_room_vertices = why.leaf_room_vertices;
    s.interior_vertices = why.interior_vertices;
  }
  return report ? std::move(*report) : check_net(mesh, net);
}

}  // namespace

UnfoldFailedException::UnfoldFailedException(std::size_t overlaps, std::size_t iterations,
                                             std::size_t faces, std::size_t input_faces)
    : std::runtime_error("no overlap-free net within the time limit (" + std::to_string(overlaps) +
                         " overlapping face pairs left after " + std::to_string(iterations) +
                         " iterations); try another seed or strategy, or a longer time limit"),
      overlaps(overlaps),
      iterations(iterations),
      faces(faces),
      input_faces(input_faces) {}

UnfoldOutcome run_pipeline(const JobInput& input, const JobOptions& options,
                           const PipelineLimits& limits, const DocumentRequest& documents,
                           PipelineProgress& progress) {
  const auto start = Clock::now();
  const double time_limit = options.time_limit.value_or(limits.default_time_limit);
  Validated v = load_and_validate(input, options, limits, progress);
  Relay relay(progress, v.input, options, documents);

  // A low-poly version to print instead of the input, when asked for: the net is then
  // approximate, its distance measured to the input.
  UnfoldOutcome out;
  std::optional<Mesh> simple =
      simplify_mesh(v.mesh, collapses_of(options.strategy), options.simplify.value_or(0), relay);
  Unfolded u;
  try {
    u = unfold_mesh(simple ? *simple : v.mesh, v.input, options, time_limit, relay);
  } catch (UnfoldFailedException& e) {
    e.seconds = seconds_since(start);
    throw;
  }
  if (simple) {
    out.simplified = true;
    u.complete = false;
    u.hausdorff = approximation_distance(v.mesh, u.mesh);
  }
  const double seconds = seconds_since(start);

  // The pass gets what is left of the time limit, and at least kMinTabRoomSeconds.
  const double left = std::max(time_limit - seconds_since(start), kMinTabRoomSeconds);
  const NetCheckReport check =
      make_room_for_tabs(u.mesh, u.net, options, left, relay, out.tab_room);
  if (!check.ok()) throw std::logic_error("the net fails the net checker: " + check.summary());

  ProgressInfo info;
  info.phase = "write";
  info.faces = u.mesh.faces.size();
  info.input_faces = v.input.faces;
  progress.report(info);
  const NetBoxMetrics box = net_metrics(u.mesh, u.net);
  NetDocument& doc = out.net;
  doc.result = u.complete ? "complete" : "approximate";
  doc.strategy = strategy_name(options.strategy);
  doc.input = v.input;
  doc.metrics.faces = u.mesh.faces.size();
  doc.metrics.coverage = box.coverage;
  doc.metrics.aspect_ratio = box.aspect_ratio;
  doc.metrics.hausdorff = u.hausdorff;
  doc.metrics.overlaps = 0;
  doc.metrics.seconds = seconds;
  doc.mesh = std::move(u.mesh);
  doc.net = std::move(u.net);
  out.iterations = u.iterations;
  write_documents(options, documents, out);
  return out;
}

}  // namespace papernet
