#pragma once
// The published figures we compare against: the Appendix C table (detailed timings) of
// Zawallich and Pajarola, "Unfolding via Progressive Mesh Approximation".

#include <string>
#include <vector>

namespace papernet::bench {

/// One cell group of the paper's table: one strategy at one resolution.
struct PaperResult {
  std::string strategy;                    ///< our name: QQ, SEMP, SEQ, TU
  int resolution = 0;                      ///< faces
  double median = 0, mean = 0, max = 0;    ///< seconds (min is 0.000 everywhere)
  double success = 0, success_approx = 0;  ///< percent
};

/// The paper's name for one of our strategies ("QQ" -> "Q/Q"); the name itself when unknown.
std::string paper_strategy_name(const std::string& strategy);

/// All 40 entries of the table (4 strategies x 10 resolutions).
const std::vector<PaperResult>& paper_results();

/// The paper's entry for a strategy and resolution, nullptr when it has none.
const PaperResult* paper_result(const std::string& strategy, int resolution);

/// The paper's machine and setup, as it describes them.
inline constexpr const char* kPaperMachine =
    "Intel i7-10700K (3.8 GHz), 128 GB RAM, Linux; C++, one thread per run, no time limit";
inline constexpr const char* kPaperData =
    "2,800 Thingi10K meshes (manifold, one component, >= 2,000 faces), each at 10 resolutions";

}  // namespace papernet::bench
