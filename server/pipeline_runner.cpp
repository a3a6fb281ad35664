#include "server/pipeline_runner.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "api/net_json.h"
#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/validate.h"
#include "core/unfold/net_check.h"
#include "core/unfold/progressive.h"
#include "core/unfold/unfolding.h"
#include "server/pipeline_output.h"
#include "server/problem.h"

namespace papernet::server {
namespace {

using Clock = std::chrono::steady_clock;

// Seconds the tab-room pass gets even when the unfolder used the job's whole time limit; the
// service's grace beyond the limit (ServiceSettings::hard_time_grace, 5 s) covers it and the
// final render.
constexpr double kMinTabRoomSeconds = 1;

// The job's time limit in seconds (the service always fills it in; 60 as a fallback).
double time_limit_of(const JobOptions& options) { return options.time_limit.value_or(60); }

struct Validated {
  Mesh mesh;
  NetInput input;
};

// Loads and validates; what cannot be unfolded fails here with the validator's reasons (422).
Validated load_and_validate(const JobInput& input, const JobOptions& options,
                            const PipelineLimits& limits, JobSink& sink) {
  LoadOptions load_options;
  load_options.max_bytes = limits.max_bytes;
  // A count over the limit is refused by the loader before it allocates (LimitExceeded: 413).
  load_options.max_faces = limits.max_faces;
  load_options.external_files = input.external_files;
  ProgressInfo info;
  info.phase = "load";
  sink.report(info);
  LoadedMesh loaded = load_mesh(input.mesh, input.format, load_options);
  info.input_faces = loaded.mesh.faces.size();
  info.faces = info.input_faces;
  info.phase = "validate";
  sink.report(info);
  if (loaded.mesh.faces.size() > limits.max_faces)
    throw ApiError("too_many_faces", "the mesh has " + std::to_string(loaded.mesh.faces.size()) +
                                         " faces; this server unfolds at most " +
                                         std::to_string(limits.max_faces));
  ValidateOptions validate_options;
  validate_options.keep_largest_component = options.keep_largest_component;
  ValidationReport report = validate(loaded, validate_options);
  if (!report.unfoldable()) {
    nlohmann::json reasons = nlohmann::json::array();
    for (const papernet::Problem& p : report.problems)
      if (p.blocking)
        reasons.push_back({{"code", p.code}, {"message", p.message}, {"elements", p.elements}});
    throw ApiError("invalid_mesh", report.reason(),
                   {{"reasons", reasons},
                    {"mesh",
                     {{"vertices", report.vertices},
                      {"faces", report.faces},
                      {"components", report.components},
                      {"genus", report.genus},
                      {"boundary_loops", report.boundary_loops}}}});
  }
  if (sink.cancelled()) throw CancelledException();
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

// Everything a client can download, from one overlap-free net.
JobOutput render(const Mesh& mesh, const Net& net, const NetInput& input, const JobOptions& options,
                 const std::string& result, double seconds, double hausdorff,
                 const nlohmann::json& level) {
  const PrintFiles print = render_print_files(mesh, net, options);
  NetDocument doc;
  doc.result = result;
  doc.strategy = strategy_name(options.strategy);
  doc.input = input;
  doc.mesh = mesh;
  doc.net = net;
  doc.metrics.faces = mesh.faces.size();
  doc.metrics.coverage = print.coverage;
  doc.metrics.aspect_ratio = print.aspect_ratio;
  doc.metrics.overlaps = 0;
  doc.metrics.seconds = seconds;
  doc.metrics.hausdorff = hausdorff;
  nlohmann::json json = net_to_json(doc);
  if (!level.is_null()) json["level"] = level;

  JobOutput out;
  out.approximate = result != "complete";
  out.input_faces = input.faces;
  out.faces = mesh.faces.size();
  out.overlaps = 0;
  out.metrics = json["metrics"];
  out.metrics["pages"] = print.pages;
  out.metrics["cut_edges"] = print.cut_edges;
  out.metrics["glue_tabs"] = print.tabs;
  out.metrics["glue_strips"] = print.strips;
  out.files["net.json"] = {"application/json", json.dump()};
  out.files["net.svg"] = {"image/svg+xml", print.svg};
  out.files["net.pdf"] = {"application/pdf", print.pdf};
  out.files["mesh.glb"] = {"model/gltf-binary", print.glb};
  return out;
}

// The core algorithms' Progress, forwarded to the job. Intermediate nets are rendered at most
// every two seconds: rendering costs time the unfolder could use.
class JobProgress : public Progress {
 public:
  JobProgress(JobSink& sink, const NetInput& input, const JobOptions& options)
      : sink_(sink), input_(input), options_(options) {}
  void report(const ProgressInfo& info) override {
    ProgressInfo copy = info;
    if (copy.input_faces == 0) copy.input_faces = input_.faces;
    sink_.report(copy);
  }
  void intermediate(const Mesh& mesh, const Net& net) override {
    const auto now = Clock::now();
    if (rendered_ && now - last_ < std::chrono::seconds(2)) return;
    rendered_ = true;
    last_ = now;
    const nlohmann::json level = {
        {"kind", "intermediate"}, {"faces", mesh.faces.size()}, {"input_faces", input_.faces}};
    sink_.intermediate(render(mesh, net, input_, options_, "approximate", 0, 0, level));
  }
  bool cancelled() override { return sink_.cancelled(); }

 private:
  JobSink& sink_;
  const NetInput& input_;
  const JobOptions& options_;
  bool rendered_ = false;
  Clock::time_point last_;
};

// The net of the job's strategy: plain Tabu Unfolding (TU) or progressive unfolding.
struct Unfolded {
  Mesh mesh;  // what the net folds into (a coarser mesh when approximate)
  Net net;
  bool complete = true;
  double hausdorff = 0;
};

// The collapses of a progressive strategy; none for TU.
std::optional<CollapseStrategy> collapse_strategy(Strategy strategy) {
  return parse_collapse_strategy(strategy_name(strategy));
}

Unfolded unfold_mesh(const Mesh& mesh, const NetInput& input, const JobOptions& options,
                     Progress& progress) {
  TabuOptions tabu;
  tabu.seed = options.seed;
  tabu.time_limit_seconds = time_limit_of(options);
  tabu.input_faces = input.faces;
  auto no_net = [](std::size_t overlaps, std::size_t iterations) {
    return ApiError("unfold_failed",
                    "no overlap-free net within the time limit (" + std::to_string(overlaps) +
                        " overlapping face pairs left after " + std::to_string(iterations) +
                        " iterations); try another seed, strategy or a longer time_limit");
  };
  if (options.strategy == Strategy::TU) {
    UnfoldResult r = unfold_tabu(mesh, tabu, progress);
    if (!r.overlap_free) throw no_net(r.overlaps, r.stats.iterations);
    return {mesh, std::move(r.net), true, 0};
  }
  ProgressiveOptions p;
  p.strategy = *collapse_strategy(options.strategy);
  p.target_faces = options.target_faces.value_or(0);
  p.tabu = tabu;
  ProgressiveResult r = unfold_progressive(mesh, p, progress);
  if (!r.overlap_free) throw no_net(r.overlaps, r.stats.iterations);
  return {std::move(r.mesh), std::move(r.net), r.complete, r.hausdorff};
}

// The net of the job: of the mesh itself, or of its low-poly version when the job asks for one
// (`simplify`), which makes the result approximate (its distance measured to the mesh).
Unfolded unfold(const Mesh& mesh, const NetInput& input, const JobOptions& options,
                Progress& progress) {
  const std::optional<Mesh> simple =
      simplify_mesh(mesh, collapse_strategy(options.strategy).value_or(CollapseStrategy::QQ),
                    options.simplify.value_or(0), progress);
  if (!simple) return unfold_mesh(mesh, input, options, progress);
  Unfolded u = unfold_mesh(*simple, input, options, progress);
  u.complete = false;
  u.hausdorff = approximation_distance(mesh, u.mesh);
  return u;
}

}  // namespace

JobRunner make_pipeline_runner(PipelineLimits limits) {
  return [limits](const JobInput& input, const JobOptions& options, JobSink& sink) -> JobOutput {
    const auto start = Clock::now();
    const Validated v = load_and_validate(input, options, limits, sink);
    JobProgress progress(sink, v.input, options);
    Unfolded u = unfold(v.mesh, v.input, options, progress);
    if (options.tabs == TabMode::Auto && options.tab_room_budget > 0) {
      ProgressInfo info;
      info.phase = "tabs";  // changing cuts so that glue tabs fit (docs/tabs.md, stage 0)
      info.faces = u.mesh.faces.size();
      info.input_faces = v.input.faces;
      sink.report(info);
    }
    // The pass gets what is left of the job's time limit, and at least kMinTabRoomSeconds (the
    // service allows some grace beyond the limit for this and for writing the files).
    const double left =
        time_limit_of(options) - std::chrono::duration<double>(Clock::now() - start).count();
    const NetCheckReport check =
        make_room_for_tabs(u.mesh, u.net, options, std::max(left, kMinTabRoomSeconds), progress);
    if (!check.ok())
      throw std::logic_error("the unfolder's net fails the net checker: " + check.summary());
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    ProgressInfo info;
    info.phase = "write";
    info.faces = u.mesh.faces.size();
    info.input_faces = v.input.faces;
    sink.report(info);
    return render(u.mesh, u.net, v.input, options, u.complete ? "complete" : "approximate", seconds,
                  u.hausdorff, nullptr);
  };
}

}  // namespace papernet::server
