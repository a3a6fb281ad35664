// The pipeline's first step: the model's bytes to the parts to unfold.
#include <cctype>
#include <string>
#include <utility>

#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/repair.h"
#include "core/mesh/validate.h"
#include "engine/internal/steps.h"

namespace papernet::engine_detail {
namespace {

NetInput counts_of(const ValidationReport& report) {
  NetInput in;
  in.vertices = report.vertices;
  in.faces = report.faces;
  in.components = report.components;
  in.genus = static_cast<int>(report.genus);
  in.boundaries = report.boundary_loops;
  return in;
}

// A loader's note ("3 line elements were skipped") as a repair entry: its leading number is
// the count. A texture or an OBJ material library that cannot be used has its own code.
NetRepair skipped(const std::string& note) {
  if (note.starts_with("texture")) return {"texture_not_used", 1, note};
  if (note.starts_with("material library")) return {"material_library_not_used", 1, note};
  std::size_t count = 0, i = 0;
  while (i < note.size() && std::isdigit(static_cast<unsigned char>(note[i])))
    count = 10 * count + static_cast<std::size_t>(note[i++] - '0');
  return {"skipped_on_load", i > 0 ? count : 1, note};
}

// Refuses what no repair can fix: no faces, non-finite coordinates.
void refuse_unrepairable(const LoadedMesh& loaded) {
  ValidationReport report = validate(loaded);
  for (const MeshProblem& p : report.problems)
    if (p.blocking && (p.code == "empty_mesh" || p.code == "non_finite_coordinates"))
      throw InvalidMeshException(std::move(report));
}

}  // namespace

LoadedMesh load_input(const JobInput& job, const PipelineLimits& limits, Progress& progress) {
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
  return loaded;
}

Prepared prepare(LoadedMesh loaded, const JobOptions& options, Progress& progress) {
  Prepared out;
  out.format = loaded.format;
  for (const std::string& note : loaded.notes) out.repairs.push_back(skipped(note));
  const bool largest = options.components == Components::Largest;
  Mesh mesh;
  MeshColour colour;
  if (options.strict) {
    // Today's judgement: any fault refused, several parts too unless only the largest is asked
    // for (then only it is judged).
    ValidateOptions validate_options;
    validate_options.keep_largest_component = largest;
    ValidationReport report = validate(loaded, validate_options);
    if (!report.unfoldable()) throw InvalidMeshException(std::move(report));
    mesh = std::move(loaded.mesh);
    colour = std::move(loaded.colour);
  } else {
    refuse_unrepairable(loaded);
    RepairResult repaired = repair_mesh(loaded.mesh, loaded.raw_faces);
    for (MeshRepair& r : repaired.repairs)
      out.repairs.push_back({std::move(r.code), r.count, std::move(r.message)});
    mesh = std::move(repaired.mesh);
    colour = remap_corners(loaded.colour, repaired.corners);
  }
  if (progress.cancelled()) throw CancelledException();
  ValidationReport report = validate(mesh);
  if (mesh.faces.empty() && !report.problems.empty() &&
      report.problems.front().code == "empty_mesh") {
    // Every face the file has was repaired away (all of zero area, say): say which repairs.
    std::string repairs;
    for (const NetRepair& r : out.repairs) repairs += (repairs.empty() ? "" : "; ") + r.message;
    if (!repairs.empty())
      report.problems.front().message = "the mesh has no faces left after repair: " + repairs;
  }
  if (!options.strict)
    for (const MeshProblem& p : report.problems)
      if (p.blocking && p.code != "several_components")  // repair leaves none: a bug if it did
        throw InvalidMeshException(std::move(report));
  out.input = counts_of(report);
  std::vector<std::vector<int>> faces_of;
  out.parts = split_components(mesh, &faces_of);
  if (!colour.empty())
    for (const std::vector<int>& faces : faces_of) {
      out.part_colours.push_back(select_faces(colour, faces));
      out.part_colours.back().materials.clear();
      out.part_colours.back().textures.clear();
    }
  out.colour.materials = std::move(colour.materials);
  out.colour.textures = std::move(colour.textures);
  if (largest && out.parts.size() > 1) {
    std::size_t dropped = 0;
    for (std::size_t p = 1; p < out.parts.size(); ++p) dropped += out.parts[p].faces.size();
    out.repairs.push_back({"dropped_components", out.parts.size() - 1,
                           "kept the largest of " + std::to_string(out.parts.size()) + " parts (" +
                               std::to_string(out.parts[0].faces.size()) + " of " +
                               std::to_string(report.faces) + " faces); dropped " +
                               std::to_string(out.parts.size() - 1) + " parts, " +
                               std::to_string(dropped) + " faces"});
    out.parts.resize(1);
    if (!out.part_colours.empty()) out.part_colours.resize(1);
  }
  return out;
}

}  // namespace papernet::engine_detail

namespace papernet {

InputReport inspect_input(const JobInput& input, const JobOptions& options,
                          const PipelineLimits& limits) {
  PipelineProgress quiet;
  LoadedMesh loaded = engine_detail::load_input(input, limits, quiet);
  InputReport out;
  out.format = loaded.format;
  out.raw_vertices = loaded.raw_vertices;
  out.as_loaded = validate(loaded);
  try {
    const engine_detail::Prepared prepared =
        engine_detail::prepare(std::move(loaded), options, quiet);
    out.repairs = prepared.repairs;
    out.repaired = prepared.input;
    out.pieces = prepared.parts.size();
  } catch (const InvalidMeshException& e) {
    out.refusal = e.what();
  }
  return out;
}

}  // namespace papernet
