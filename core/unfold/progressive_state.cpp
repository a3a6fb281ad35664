// The state of a progressive unfolding (core/unfold/internal/progressive_state.h): the
// unfolding of the collapsed mesh with its id maps to the input, vertex splits applied to it, and
// its net in the input's ids.
#include "core/unfold/internal/progressive_state.h"

#include <array>
#include <utility>

#include "core/errors.h"
#include "core/mesh/dual_graph.h"
#include "core/random.h"

namespace papernet::progressive_detail {
namespace {

// Budget of the local repair after a split, before the Tabu Unfolder runs: moved-face tests. Its
// sides grow fourfold from 16 faces while no move helps, up to the whole mesh: on large meshes
// the cuts on the tree path between a new overlapping pair often have no side under 256 faces,
// and the repair's many ways of gluing a side back (any face near the cut) find a move where the
// Tabu Unfolder's walks take hundreds of iterations. c3d__rocker-arm (20,088 faces, seed 1,
// docs/performance.md): with sides of at most 256 faces and 4,000 + 4 tests per face, 42 Tabu
// runs after splits took 17.4 s of a 22.9 s unfold; with these, 16 runs took 2.7 s of 7.8 s.
// Neutral on bench/1000-2000.
constexpr std::size_t kRepairTestsBase = 256'000;
constexpr std::size_t kRepairTestsPerFace = 256;

}  // namespace

std::size_t repair_tests(const Unfolding& u) {
  return kRepairTestsBase + kRepairTestsPerFace * u.face_count();
}

std::uint64_t split_seed(std::uint64_t seed, std::size_t index) {
  return seed ^ (0x9e3779b97f4a7c15ULL * (index + 1));
}

// Applies a vertex split to the unfolding's mesh and tree (update() not yet called).
void apply_split(State& st, const VertexSplit& s, std::uint64_t seed) {
  Unfolding& u = st.unfolding;
  ++st.splits;
  const int r = u.add_vertex(s.vertex_position);
  st.vertex[s.vertex] = r;
  u.set_vertex_position(st.vertex[s.moved], s.moved_to);
  for (const auto& [f, c] : s.relabelled) {
    std::array<int, 3> corners = u.mesh().faces[st.face[f]];
    corners[c] = r;
    u.set_face_corners(st.face[f], corners);
  }
  for (const SplitFace& nf : s.new_faces) {
    std::array<int, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = st.vertex[nf.corners[k]];
    st.face[nf.face] = u.add_face(corners);
  }
  Random rng(seed);
  for (const SplitFace& nf : s.new_faces) {
    const int f = st.face[nf.face];
    const int a = nf.wing[0] >= 0 ? st.face[nf.wing[0]] : -1;
    const int b = nf.wing[1] >= 0 ? st.face[nf.wing[1]] : -1;
    if (a >= 0 && b >= 0 && u.parent(b) == a) {
      u.insert_between(f, a, b);
    } else if (a >= 0 && b >= 0 && u.parent(a) == b) {
      u.insert_between(f, b, a);
    } else {
      // A leaf of a random neighbour already in the tree: a wing face or the other new face.
      int options[3], n = 0;
      for (int x : {a, b})
        if (x >= 0) options[n++] = x;
      for (const SplitFace& other : s.new_faces) {
        const int g = st.face[other.face];
        if (g != f && u.parent(g) != -2) options[n++] = g;
      }
      if (n == 0) throw TopologyException("a split face has no neighbour in the unfold tree");
      u.attach(f, options[rng.below(static_cast<std::uint64_t>(n))]);
    }
  }
}

// Applies splits and lays them out. When faces overlap, local moves of small parts of the tree
// are tried first (Unfolding::repair_locally, O(moved side) each) before the caller falls back on
// the Tabu Unfolder: most new overlaps are local. Returns the overlap count.
std::size_t place_splits(State& st, const std::vector<VertexSplit>& splits, std::uint64_t seed) {
  for (std::size_t i = 0; i < splits.size(); ++i) apply_split(st, splits[i], seed + i);
  Unfolding& u = st.unfolding;
  if (u.update() == 0) return 0;
  LocalRepairOptions repair;
  repair.max_side = u.face_count();
  repair.max_tests = repair_tests(u);
  return u.repair_locally(repair);
}

// The unfolding of pm's current mesh from the steepest-edge tree of `seed`, with id maps. A
// retry (`retry`) starts from the minimum-perimeter tree instead when it has fewer overlapping
// pairs: on CAD meshes of slivers it often has none where steepest edges have thousands (the
// Twin plate at 486 faces: 0 against 5,931).
State make_state(const ProgressiveMesh& pm, const Mesh& input, std::uint64_t seed, bool retry) {
  std::vector<int> face_ids, vertex_ids;
  Mesh coarse = pm.compact(&face_ids, &vertex_ids);
  Unfolding start = Unfolding::steepest_edge(coarse, seed);
  if (retry && start.overlap_count() > 0) {
    Unfolding other(coarse, min_perimeter_tree(coarse, build_dual_graph(coarse), seed));
    if (other.overlap_count() < start.overlap_count()) start = std::move(other);
  }
  State st{std::move(start), std::vector<int>(pm.input_face_count(), -1),
           std::vector<int>(input.vertices.size(), -1)};
  for (std::size_t i = 0; i < face_ids.size(); ++i) st.face[face_ids[i]] = static_cast<int>(i);
  for (std::size_t i = 0; i < vertex_ids.size(); ++i)
    st.vertex[vertex_ids[i]] = static_cast<int>(i);
  return st;
}

// The net of `mesh`'s steepest-edge tree, else of its minimum-perimeter tree, when one of them
// has no overlapping pair. One state of the input at a time: on a 100,000-face input each takes
// about 50 MB (both at once made nefertiti's peak 173 MB instead of 72 MB).
std::optional<Net> start_tree_net(const Mesh& mesh, std::uint64_t seed) {
  {
    const Unfolding steepest = Unfolding::steepest_edge(mesh, seed);
    if (steepest.overlap_count() == 0) return steepest.net();
  }
  std::vector<int> parent = min_perimeter_tree(mesh, build_dual_graph(mesh), seed);
  const Unfolding other(mesh, parent);
  if (other.overlap_count() == 0) return other.net();
  return std::nullopt;
}

// ProgressiveOptions::complete_first: the tree the uncollapse stopped with, every split it had
// left applied to it without re-laying anything out, is the Tabu Unfolder's start on the input
// (unfold_tabu_from, which starts again elsewhere when it stalls). Most of that tree is
// overlap-free already, but on the CAD parts of bench/800-2000 where QQ stops it needs about as
// much work as a fresh start: fewer moved-face tests in 7 of 16 runs (docs/performance.md).
UnfoldResult finish_on_input(State st, ProgressiveMesh& pm, const Mesh& input, std::uint64_t seed,
                             std::size_t index, const TabuOptions& tabu, Progress& progress) {
  while (pm.splits_left() > 0) apply_split(st, pm.split(), split_seed(seed, index++));
  std::vector<int> input_face(st.unfolding.face_count(), -1);
  for (std::size_t f = 0; f < input.faces.size(); ++f) input_face[st.face[f]] = static_cast<int>(f);
  std::vector<int> parent(input.faces.size(), -1);
  for (std::size_t f = 0; f < input.faces.size(); ++f) {
    const int p = st.unfolding.parent(st.face[f]);
    parent[f] = p >= 0 ? input_face[p] : -1;
  }
  return unfold_tabu_from(input, parent, tabu, progress);
}

Net net_in_input_ids(const State& st, std::size_t faces) {
  Net net;
  net.parent.assign(faces, -1);
  net.points.resize(faces);
  std::vector<int> input_face(st.unfolding.face_count(), -1);
  for (std::size_t f = 0; f < faces; ++f) input_face[st.face[f]] = static_cast<int>(f);
  for (std::size_t f = 0; f < faces; ++f) {
    const int uf = st.face[f];
    const int p = st.unfolding.parent(uf);
    net.parent[f] = p >= 0 ? input_face[p] : -1;
    net.points[f] = st.unfolding.points(uf);
  }
  return net;
}

}  // namespace papernet::progressive_detail
