// Private to core/unfold/progressive.cpp: the state progressive unfolding refines, the unfolding
// of the collapsed mesh with its ids in the input's, and the vertex splits applied to it
// (core/unfold/progressive_state.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/progressive_mesh.h"
#include "core/progress.h"
#include "core/unfold/net.h"
#include "core/unfold/tabu.h"
#include "core/unfold/unfolding.h"

namespace papernet::progressive_detail {

/// The unfolding being refined and the id maps from the input to it.
struct State {
  Unfolding unfolding;
  std::vector<int> face;    ///< input face -> Unfolding face, -1 while collapsed
  std::vector<int> vertex;  ///< input vertex -> Unfolding vertex, -1 while collapsed
  std::size_t splits = 0;   ///< splits applied
};

/// The seed of the `index`th step of the uncollapse, from the run's `seed`.
std::uint64_t split_seed(std::uint64_t seed, std::size_t index);

/// Budget of the local repair after a split, before the Tabu Unfolder runs: moved-face tests.
std::size_t repair_tests(const Unfolding& u);

/// Applies a vertex split to the unfolding's mesh and tree (update() not yet called), each new
/// face hung between its wings or from a neighbour chosen by `seed`.
void apply_split(State& st, const VertexSplit& s, std::uint64_t seed);

/// Applies splits and lays them out. When faces overlap, local moves of small parts of the tree
/// are tried first (Unfolding::repair_locally, O(moved side) each) before the caller falls back
/// on the Tabu Unfolder: most new overlaps are local. Returns the overlap count.
std::size_t place_splits(State& st, const std::vector<VertexSplit>& splits, std::uint64_t seed);

/// The unfolding of pm's current mesh from the steepest-edge tree of `seed`, with id maps. A
/// retry (`retry`) starts from the minimum-perimeter tree instead when it has fewer overlapping
/// pairs.
State make_state(const ProgressiveMesh& pm, const Mesh& input, std::uint64_t seed, bool retry);

/// The net of `mesh`'s steepest-edge tree, else of its minimum-perimeter tree, when one of them
/// has no overlapping pair.
std::optional<Net> start_tree_net(const Mesh& mesh, std::uint64_t seed);

/// ProgressiveOptions::complete_first: every split `pm` has left applied to the tree the
/// uncollapse stopped with (steps from `index` on), then the Tabu Unfolder from that tree on the
/// input.
UnfoldResult finish_on_input(State st, ProgressiveMesh& pm, const Mesh& input, std::uint64_t seed,
                             std::size_t index, const TabuOptions& tabu, Progress& progress);

/// The net of a state whose every face is the input's, in the input's face ids (`faces` faces).
Net net_in_input_ids(const State& st, std::size_t faces);

}  // namespace papernet::progressive_detail
