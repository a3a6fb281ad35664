#include "core/mesh/decimate.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <optional>
#include <queue>
#include <vector>

#include "core/errors.h"

namespace papernet {
namespace {

// Garland-Heckbert quadric: the sum of squared distances to a set of weighted planes, stored as
// the symmetric 4x4 matrix [A b; b^T c] (A 3x3), so that Q(p) = p^T A p + 2 b.p + c.
struct Quadric {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  double b0 = 0, b1 = 0, b2 = 0, c = 0;

  static Quadric plane(Vec3 n, double d, double weight) {
    Quadric q;
    q.a00 = weight * n.x * n.x;
    q.a01 = weight * n.x * n.y;
    q.a02 = weight * n.x * n.z;
    q.a11 = weight * n.y * n.y;
    q.a12 = weight * n.y * n.z;
    q.a22 = weight * n.z * n.z;
    q.b0 = weight * n.x * d;
    q.b1 = weight * n.y * d;
    q.b2 = weight * n.z * d;
    q.c = weight * d * d;
    return q;
  }
  Quadric& operator+=(const Quadric& o) {
    a00 += o.a00, a01 += o.a01, a02 += o.a02, a11 += o.a11, a12 += o.a12, a22 += o.a22;
    b0 += o.b0, b1 += o.b1, b2 += o.b2, c += o.c;
    return *this;
  }
  double operator()(Vec3 p) const {
    const double e = p.x * (a00 * p.x + 2 * a01 * p.y + 2 * a02 * p.z) +
                     p.y * (a11 * p.y + 2 * a12 * p.z) + p.z * a22 * p.z +
                     2 * (b0 * p.x + b1 * p.y + b2 * p.z) + c;
    return std::max(e, 0.0);
  }
  // The minimiser of Q (A x = -b) when A is well-conditioned, else nothing.
  std::optional<Vec3> minimum() const {
    const double c00 = a11 * a22 - a12 * a12, c01 = a02 * a12 - a01 * a22,
                 c02 = a01 * a12 - a02 * a11;
    const double det = a00 * c00 + a01 * c01 + a02 * c02;
    const double frob2 =
        a00 * a00 + a11 * a11 + a22 * a22 + 2 * (a01 * a01 + a02 * a02 + a12 * a12);
    // det is the product of the eigenvalues, frob^3 bounds the cube of the largest: a small
    // ratio means a (nearly) singular A, i.e. a flat or cylindrical neighbourhood.
    if (!(std::abs(det) > 1e-9 * frob2 * std::sqrt(frob2))) return std::nullopt;
    const double c11 = a00 * a22 - a02 * a02, c12 = a01 * a02 - a00 * a12,
                 c22 = a00 * a11 - a01 * a01;
    const double inv = -1.0 / det;
    return Vec3{inv * (c00 * b0 + c01 * b1 + c02 * b2), inv * (c01 * b0 + c11 * b1 + c12 * b2),
                inv * (c02 * b0 + c12 * b1 + c22 * b2)};
  }
};

// Weight of a boundary edge's constraint plane relative to the face planes (Garland-Heckbert
// keep open borders in place with a strong perpendicular plane).
constexpr double kBoundaryWeight = 10.0;

struct Candidate {
  int kept = -1;
  Vec3 position;
  double cost = 0, length2 = 0;
};

// A vertex's evaluations from its last push, in increasing order of `kept`, with the versions of
// both ends (Decimator::version_) they were computed with.
struct CachedCandidate {
  Candidate candidate;
  unsigned kept_version = 0;
};
struct Cached {
  unsigned version = 0;
  std::vector<CachedCandidate> entries;
};

struct HeapEntry {
  double cost, length2;
  int vertex;
  unsigned stamp;
  bool operator<(const HeapEntry& o) const {  // std::priority_queue pops the largest
    if (cost != o.cost) return cost > o.cost;
    if (length2 != o.length2) return length2 > o.length2;
    return vertex > o.vertex;
  }
};

class Decimator {
 public:
  Decimator(ProgressiveMesh& pm, CollapseStrategy strategy, bool reuse = true)
      : pm_(pm),
        strategy_(strategy),
        reuse_(reuse),
        stamp_(pm.mesh().vertices.size(), 0),
        best_(pm.mesh().vertices.size()),
        version_(pm.mesh().vertices.size(), 0),
        cached_(pm.mesh().vertices.size()) {
    if (strategy_ != CollapseStrategy::SEMP) init_quadrics();
  }

  void run(std::size_t target, Progress& progress) {
    const auto start = std::chrono::steady_clock::now();
    auto last_report = start;
    ProgressInfo info;
    info.phase = "collapse";
    info.input_faces = pm_.input_face_count();
    const std::size_t from = pm_.face_count();
    auto report = [&] {
      info.faces = pm_.face_count();
      // Collapses made of those towards the target (each removes about two faces).
      info.phase_fraction =
          from > target ? double(from - std::max(info.faces, target)) / double(from - target) : 1.0;
      info.elapsed_seconds = std::chrono::duration<double>(last_report - start).count();
      progress.report(info);
    };
    report();
    const int nv = static_cast<int>(pm_.mesh().vertices.size());
    for (int v = 0; v < nv; ++v) push(v);
    std::size_t steps = 0;
    while (pm_.face_count() > target && !heap_.empty()) {
      if (++steps % 64 == 0) {
        if (progress.cancelled()) throw CancelledException();
        const auto now = std::chrono::steady_clock::now();
        if (now - last_report > std::chrono::milliseconds(100)) {
          last_report = now;
          report();
        }
      }
      const HeapEntry top = heap_.top();
      heap_.pop();
      if (top.stamp != stamp_[top.vertex] || !pm_.vertex_alive(top.vertex)) continue;
      const Candidate& c = best_[top.vertex];
      if (!pm_.try_collapse(top.vertex, c.kept, c.position)) {
        push(top.vertex);  // its 2-ring changed since it was queued
        continue;
      }
      const int r = top.vertex, k = c.kept;
      if (!quadric_.empty()) quadric_[k] += quadric_[r];
      ++stamp_[r];
      ++version_[k];  // k's quadric and position changed: its cached evaluations are stale
      push(k);
      ring(k, around_);
      for (int w : around_) push(w);
    }
    last_report = std::chrono::steady_clock::now();
    report();
  }

 private:
  void init_quadrics() {
    const Mesh& m = pm_.mesh();
    quadric_.assign(m.vertices.size(), Quadric{});
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      if (!pm_.face_alive(static_cast<int>(f))) continue;  // collapsed earlier
      const auto& face = m.faces[f];
      const Vec3 p = m.vertices[face[0]];
      const Vec3 n2 = cross(m.vertices[face[1]] - p, m.vertices[face[2]] - p);
      const double len = norm(n2);
      if (len == 0) continue;
      const Vec3 n = (1 / len) * n2;
      const Quadric q = Quadric::plane(n, -dot(n, p), 0.5 * len);
      for (int c : face) quadric_[c] += q;
      // Boundary edges: a plane through the edge, perpendicular to the face.
      for (int i = 0; i < 3; ++i) {
        const int a = face[i], b = face[(i + 1) % 3];
        if (!boundary_edge(a, b)) continue;
        const Vec3 e = m.vertices[b] - m.vertices[a];
        const Vec3 side = cross(e, n);
        const double sl = norm(side);
        if (sl == 0) continue;
        const Vec3 u = (1 / sl) * side;
        const Quadric qb = Quadric::plane(u, -dot(u, m.vertices[a]), kBoundaryWeight * dot(e, e));
        quadric_[a] += qb;
        quadric_[b] += qb;
      }
    }
  }

  bool boundary_edge(int a, int b) const {
    int count = 0;
    for (int f : pm_.vertex_faces(a)) {
      const auto& face = pm_.mesh().faces[f];
      if (face[0] == b || face[1] == b || face[2] == b) ++count;
    }
    return count == 1;
  }

  // v's neighbours in increasing order. v's faces form one consistently oriented fan: each
  // neighbour follows v in exactly one face, except, in an open fan, the one at its end, which
  // only precedes v. The corners around v then XOR to that end and the fan's start (distinct).
  void ring(int v, std::vector<int>& out) const {
    out.clear();
    int ends = 0;
    const std::vector<int>& around = pm_.vertex_faces(v);
    for (int f : around) {
      const auto& face = pm_.mesh().faces[f];
      out.push_back(face[0] == v ? face[1] : face[1] == v ? face[2] : face[0]);
      ends ^= face[0] ^ face[1] ^ face[2] ^ v;
    }
    if (ends != 0) {  // open fan: add the corner before v that follows v nowhere
      for (int f : around) {
        const auto& face = pm_.mesh().faces[f];
        const int before = face[0] == v ? face[2] : face[1] == v ? face[0] : face[1];
        if (std::find(out.begin(), out.end(), before) == out.end()) {
          out.push_back(before);
          break;
        }
      }
    }
    std::sort(out.begin(), out.end());
  }

  Candidate evaluate(int r, int k) const {
    const Vec3 pr = pm_.mesh().vertices[r], pk = pm_.mesh().vertices[k];
    const Vec3 mid = 0.5 * (pr + pk);
    Candidate c;
    c.kept = k;
    c.length2 = dot(pk - pr, pk - pr);
    if (strategy_ == CollapseStrategy::SEMP) {
      c.position = mid;
      c.cost = c.length2;
      return c;
    }
    Quadric q = quadric_[r];
    q += quadric_[k];
    const std::optional<Vec3> opt = q.minimum();
    // An optimum far off the edge means A is nearly singular in some direction: fall back.
    if (opt && dot(*opt - mid, *opt - mid) <= 4 * c.length2) {
      c.position = *opt;
    } else {
      c.position = mid;
      double best = q(mid);
      for (Vec3 p : {pr, pk}) {
        const double e = q(p);
        if (e < best) best = e, c.position = p;
      }
    }
    c.cost = strategy_ == CollapseStrategy::QQ ? q(c.position) : c.length2;
    return c;
  }

  // Finds vertex v's cheapest legal collapse and queues it (nothing when none is legal).
  void push(int v) {
    ++stamp_[v];
    if (!pm_.vertex_alive(v)) return;
    ring(v, ring_);
    // evaluate(v, k) depends only on v's and k's quadrics and positions, which change only when
    // they are kept by a collapse (version_): reuse v's earlier evaluations of unchanged pairs.
    // Both lists are in increasing order of k.
    Cached& cache = cached_[v];
    candidates_.clear();
    std::size_t j = 0;
    const bool own_valid = cache.version == version_[v] && !cache.entries.empty();
    for (int k : ring_) {
      if (own_valid) {
        while (j < cache.entries.size() && cache.entries[j].candidate.kept < k) ++j;
        if (j < cache.entries.size() && cache.entries[j].candidate.kept == k &&
            cache.entries[j].kept_version == version_[k]) {
          candidates_.push_back(cache.entries[j].candidate);
          continue;
        }
      }
      candidates_.push_back(evaluate(v, k));
    }
    if (reuse_) {
      cache.version = version_[v];
      cache.entries.resize(candidates_.size());
      for (std::size_t i = 0; i < candidates_.size(); ++i)
        cache.entries[i] = {candidates_[i], version_[candidates_[i].kept]};
    }
    // The cheapest few only, cheapest first: around a vertex of high valence, checking every
    // edge is slow. Selected one at a time, not sorted: the first is nearly always legal.
    const auto cheaper = [](const Candidate& a, const Candidate& b) {
      if (a.cost != b.cost) return a.cost < b.cost;
      if (a.length2 != b.length2) return a.length2 < b.length2;
      return a.kept < b.kept;
    };
    const std::size_t tries = std::min<std::size_t>(candidates_.size(), 12);
    for (std::size_t i = 0; i < tries; ++i) {
      std::size_t min = i;
      for (std::size_t m = i + 1; m < candidates_.size(); ++m)
        if (cheaper(candidates_[m], candidates_[min])) min = m;
      std::swap(candidates_[i], candidates_[min]);
      const Candidate& c = candidates_[i];
      if (!pm_.can_collapse(v, c.kept, c.position)) continue;
      best_[v] = c;
      heap_.push({c.cost, c.length2, v, stamp_[v]});
      return;
    }
  }

  ProgressiveMesh& pm_;
  CollapseStrategy strategy_;
  bool reuse_;
  std::vector<Quadric> quadric_;
  std::vector<unsigned> stamp_;
  std::vector<Candidate> best_;
  std::vector<unsigned> version_;
  std::vector<Cached> cached_;
  std::vector<int> around_;
  std::priority_queue<HeapEntry> heap_;
  std::vector<int> ring_;
  std::vector<Candidate> candidates_;
};

// Forwards cancellation only: a further collapse during unfolding is not a phase of its own.
class CancelOnly : public Progress {
 public:
  explicit CancelOnly(Progress& outer) : outer_(outer) {}
  bool cancelled() override { return outer_.cancelled(); }

 private:
  Progress& outer_;
};

}  // namespace

std::string collapse_strategy_name(CollapseStrategy strategy) {
  switch (strategy) {
    case CollapseStrategy::QQ:
      return "QQ";
    case CollapseStrategy::SEMP:
      return "SEMP";
    case CollapseStrategy::SEQ:
      return "SEQ";
  }
  return "?";
}

std::size_t collapse_target(std::size_t input_faces, int genus) {
  const double f = static_cast<double>(input_faces);
  const double t = f / 10 + std::sqrt(f) * (1 + std::max(genus, 0));
  return static_cast<std::size_t>(std::llround(t));
}

ProgressiveMesh decimate(const Mesh& mesh, const DecimateOptions& options, Progress& progress) {
  ProgressiveMesh pm(mesh);
  const std::size_t target = options.target_faces > 0
                                 ? options.target_faces
                                 : collapse_target(pm.input_face_count(), pm.genus());
  Decimator(pm, options.strategy, options.reuse_evaluations).run(target, progress);
  return pm;
}

void collapse_further(ProgressiveMesh& pm, CollapseStrategy strategy, std::size_t target_faces,
                      Progress& progress) {
  CancelOnly quiet(progress);
  Decimator(pm, strategy).run(target_faces, quiet);
}

}  // namespace papernet
