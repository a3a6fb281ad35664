#include "bench/paper_results.h"

namespace papernet::bench {

namespace {

// Columns per resolution: median, mean, max seconds; success regular and incl. approximations.
struct Column {
  const char* strategy;
  double median[10], mean[10], max[10], success[10], approx[10];
};

constexpr int kResolutions[10] = {100, 200, 400, 600, 800, 1000, 1250, 1500, 1750, 2000};

// Typed in from the table; the test checks a few cells against the paper's text.
constexpr Column kTable[4] = {
    {"QQ",
     {0.018, 0.166, 1.300, 3.623, 8.037, 13.978, 26.812, 40.205, 63.685, 87.213},
     {0.049, 0.544, 6.170, 22.027, 52.701, 90.594, 168.444, 248.333, 433.656, 659.311},
     {2.396, 23.006, 248.122, 892.522, 2090.394, 4583.610, 7350.622, 13703.176, 24035.986,
      37216.614},
     {99.964, 99.179, 98.571, 98.071, 97.857, 97.679, 97.464, 97.286, 97.036, 97.143},
     {100.000, 100.000, 99.964, 100.000, 100.000, 99.929, 99.929, 99.893, 99.857, 99.786}},
    {"SEMP",
     {0.020, 0.174, 1.544, 5.058, 11.630, 22.656, 44.340, 76.985, 118.837, 178.930},
     {0.050, 0.598, 6.031, 21.116, 50.592, 98.783, 199.345, 324.464, 549.684, 728.359},
     {2.082, 25.837, 253.816, 800.405, 2249.449, 4363.279, 9175.251, 15587.310, 26133.299,
      39559.031},
     {99.786, 98.857, 98.429, 98.107, 97.714, 97.536, 97.500, 97.321, 97.036, 97.250},
     {100.000, 100.000, 99.750, 99.607, 99.607, 99.607, 99.679, 99.571, 99.607, 99.679}},
    {"SEQ",
     {0.018, 0.168, 1.408, 4.464, 10.205, 18.689, 34.885, 57.719, 90.264, 130.008},
     {0.049, 0.575, 5.724, 21.636, 45.994, 87.323, 160.896, 285.741, 457.902, 626.908},
     {2.983, 27.673, 247.668, 903.418, 2228.795, 4517.269, 8201.845, 16143.076, 26603.642,
      39313.610},
     {99.786, 98.893, 98.250, 98.250, 97.786, 98.071, 97.893, 97.929, 97.679, 97.679},
     {100.000, 99.964, 99.643, 99.679, 99.643, 99.643, 99.643, 99.643, 99.607, 99.571}},
    {"TU",
     {0.015, 0.135, 1.020, 3.432, 8.129, 15.857, 31.149, 56.416, 91.944, 140.888},
     {0.030, 0.282, 2.257, 6.940, 19.106, 42.305, 88.723, 141.768, 246.291, 352.958},
     {1.104, 23.238, 198.557, 607.050, 1150.672, 3586.101, 7747.810, 8964.870, 11152.966,
      20322.664},
     {100.000, 99.750, 99.643, 99.536, 99.464, 99.357, 99.321, 99.107, 99.000, 98.929},
     {100.000, 99.750, 99.643, 99.536, 99.464, 99.357, 99.321, 99.107, 99.000, 98.929}},
};

}  // namespace

std::string paper_strategy_name(const std::string& strategy) {
  if (strategy == "QQ") return "Q/Q";
  if (strategy == "SEMP") return "SE/MP";
  if (strategy == "SEQ") return "SE/Q";
  return strategy;
}

const std::vector<PaperResult>& paper_results() {
  static const std::vector<PaperResult> results = [] {
    std::vector<PaperResult> all;
    for (const Column& c : kTable)
      for (int i = 0; i < 10; ++i)
        all.push_back({c.strategy, kResolutions[i], c.median[i], c.mean[i], c.max[i], c.success[i],
                       c.approx[i]});
    return all;
  }();
  return results;
}

const PaperResult* paper_result(const std::string& strategy, int resolution) {
  for (const PaperResult& r : paper_results())
    if (r.strategy == strategy && r.resolution == resolution) return &r;
  return nullptr;
}

}  // namespace papernet::bench
