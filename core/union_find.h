#pragma once

#include <cstddef>
#include <numeric>
#include <vector>

namespace papernet {

/// Disjoint sets of 0 … n-1 (union-find with path halving): faces of one part, corners of one
/// fan, edges of one boundary loop.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : up_(n) { std::iota(up_.begin(), up_.end(), 0); }
  /// The representative of x's set.
  int find(int x) {
    while (up_[x] != x) x = up_[x] = up_[up_[x]];
    return x;
  }
  /// Joins the sets of a and b; false when they were one already.
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    up_[a] = b;
    return true;
  }

 private:
  std::vector<int> up_;
};

}  // namespace papernet
