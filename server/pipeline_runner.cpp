#include "server/pipeline_runner.h"

#include "server/job_json.h"

namespace papernet::server {
namespace {

// What the service serves of every result, final or intermediate.
constexpr DocumentRequest kDocuments{.svg = true, .svg_pages = true, .pdf = true, .glb = true};

JobOutput job_output(const UnfoldOutcome& outcome) {
  JobOutput out;
  out.approximate = outcome.net.result != "complete";
  out.input_faces = outcome.net.input.faces;
  out.faces = outcome.net.mesh.faces.size();
  out.overlaps = 0;
  out.metrics = net_to_json(outcome.net)["metrics"];
  if (outcome.print) {
    out.metrics["pages"] = outcome.print->pages;
    out.metrics["cut_edges"] = outcome.print->cut_edges;
    out.metrics["glue_tabs"] = outcome.print->tabs;
    out.metrics["glue_strips"] = outcome.print->strips;
    out.metrics["layout"] = outcome.print->layout;
    out.metrics["print_pieces"] = outcome.print->pieces;
    out.metrics["smallest_label_mm"] = outcome.print->smallest_label_mm;
    out.metrics["small_labels"] = outcome.print->small_labels;
    if (!outcome.print->layout_note.empty())
      out.metrics["layout_note"] = outcome.print->layout_note;
  }
  // Stored with the metrics (server/job.h); job_json shows them beside them.
  nlohmann::json repairs = nlohmann::json::array(), pieces = nlohmann::json::array();
  for (const NetRepair& r : outcome.net.repairs)
    repairs.push_back({{"code", r.code}, {"count", r.count}, {"message", r.message}});
  for (const NetPiece& p : outcome.net.pieces)
    pieces.push_back({{"component", p.component},
                      {"result", p.result},
                      {"faces", p.faces},
                      {"hausdorff", p.hausdorff}});
  nlohmann::json warnings = nlohmann::json::array();
  for (const NetRepair& w : outcome.net.warnings)
    warnings.push_back({{"code", w.code}, {"count", w.count}, {"message", w.message}});
  out.metrics["repairs"] = std::move(repairs);
  out.metrics["warnings"] = std::move(warnings);
  out.metrics["detail"] = {{"mode", outcome.net.detail.mode}, {"faces", outcome.net.detail.faces}};
  out.metrics["pieces"] = std::move(pieces);
  if (const auto& room = outcome.tab_room)
    out.metrics["tab_room"] = {{"blocked_before", room->blocked_before},
                               {"blocked_after", room->blocked_after},
                               {"moves", room->moves},
                               {"kicks", room->kicks},
                               {"seconds", room->seconds},
                               {"leaves_without_room", room->leaves_without_room},
                               {"leaf_room_vertices", room->leaf_room_vertices},
                               {"interior_vertices", room->interior_vertices}};
  const Documents& docs = outcome.documents;
  out.files["net.json"] = {"application/json", docs.net_json};
  out.files["net.svg"] = {"image/svg+xml", docs.svg};
  out.files["net.pdf"] = {"application/pdf", docs.pdf};
  out.files["mesh.glb"] = {"model/gltf-binary", docs.glb};
  // Each printed page on its own (none without paper: net.svg is then the one drawing).
  if (outcome.net.print)
    for (std::size_t k = 0; k < docs.svg_pages.size(); ++k)
      out.files[page_file_name(k + 1)] = {"image/svg+xml", docs.svg_pages[k]};
  const std::vector<Texture>& textures = outcome.net.colour.textures;
  for (std::size_t k = 0; k < textures.size(); ++k)
    out.files[texture_file_name(k)] = {textures[k].mime_type, textures[k].bytes};
  return out;
}

// The job's sink as the pipeline's progress hook.
class SinkProgress : public PipelineProgress {
 public:
  explicit SinkProgress(JobSink& sink) : sink_(sink) {}
  void report(const ProgressInfo& info) override { sink_.report(info); }
  bool cancelled() override { return sink_.cancelled(); }
  bool wants_intermediates() const override { return true; }
  void intermediate_outcome(const UnfoldOutcome& outcome) override {
    sink_.intermediate(job_output(outcome));
  }

 private:
  JobSink& sink_;
};

}  // namespace

JobRunner make_pipeline_runner(PipelineLimits limits) {
  return [limits](const JobInput& input, const JobOptions& options, JobSink& sink) -> JobOutput {
    SinkProgress progress(sink);
    return job_output(run_pipeline(input, options, limits, kDocuments, progress));
  };
}

}  // namespace papernet::server
