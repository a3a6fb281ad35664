#include "fuzz/fuzz_pipeline.h"

#include <cstdlib>
#include <cstring>

#include "core/errors.h"
#include "core/mesh/repair.h"
#include "core/mesh/validate.h"
#include "engine/pipeline.h"

namespace papernet::fuzz {

void load_and_validate(std::string_view bytes, MeshFormat format,
                       const std::map<std::string, std::string>& external_files) {
  const PipelineLimits limits;
  LoadOptions options;
  options.max_bytes = limits.max_bytes;
  options.max_faces = limits.max_faces * 4 + 16;
  options.external_files = external_files;
  LoadedMesh loaded;
  try {
    loaded = load_mesh(bytes, format, options);
  } catch (const IOException& e) {
    if (std::strlen(e.what()) == 0) std::abort();  // a refusal must name the fault
    return;
  }
  // validate()'s precondition, which load_mesh promises.
  for (const auto& f : loaded.mesh.faces)
    for (const int v : f)
      if (v < 0 || static_cast<std::size_t>(v) >= loaded.mesh.vertices.size()) std::abort();
  bool repairable = !loaded.mesh.faces.empty();
  for (const bool keep_largest : {false, true}) {
    ValidateOptions validate_options;
    validate_options.keep_largest_component = keep_largest;
    const ValidationReport report = validate(loaded, validate_options);
    if (!report.unfoldable() && report.reason().empty()) std::abort();
    for (const MeshProblem& p : report.problems)
      if (p.code == "non_finite_coordinates") repairable = false;
  }
  if (!repairable) return;
  // What the engine does next (engine/prepare.cpp): repair, then the repaired mesh must pass
  // validation but for being in several parts, and its parts must hold every face.
  const RepairResult repaired = repair_mesh(loaded.mesh, loaded.raw_faces);
  for (const MeshProblem& p : validate(repaired.mesh).problems)
    if (p.blocking && p.code != "several_components" && p.code != "empty_mesh") std::abort();
  std::size_t faces = 0;
  for (const Mesh& part : split_components(repaired.mesh)) faces += part.faces.size();
  if (faces != repaired.mesh.faces.size()) std::abort();
}

}  // namespace papernet::fuzz
