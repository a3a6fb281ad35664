// The real job runner (server/pipeline_runner) driven directly, without queue or sockets: the
// phases it reports, in order, on a real mesh.
#include "server/pipeline_runner.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/paths.h"
#include "tests/support/sanitized.h"

using namespace papernet;
using namespace papernet::server;

namespace {

struct RecordingSink : JobSink {
  std::vector<std::string> phases;
  void report(const ProgressInfo& info) override {
    if (phases.empty() || phases.back() != info.phase) phases.push_back(info.phase);
  }
  void intermediate(JobOutput) override {}
  bool cancelled() override { return false; }
};

JobInput sample_input() {
  std::ifstream in(papernet::test::test_data_dir() + "/sample.obj", std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  JobInput input;
  input.mesh = s.str();
  input.format = MeshFormat::Obj;
  return input;
}

// The job of these tests: sample.obj by TU, seed 3.
JobOptions sample_options() {
  JobOptions options;
  options.strategy = Strategy::TU;
  options.seed = 3;
  options.time_limit = 60;
  options.detail = {DetailMode::Full, 0};  // all 1,000 faces
  test::lighten(options);                  // the tab room pass and the merge still run
  return options;
}

JobOutput run_sample(const JobOptions& options, RecordingSink& sink) {
  JobOutput out = make_pipeline_runner({})(sample_input(), options, sink);
  EXPECT_EQ(out.files.count("net.pdf"), 1u);
  return out;
}

JobOutput run_sample(TabMode tabs, RecordingSink& sink) {
  JobOptions options = sample_options();
  options.tabs = tabs;
  return run_sample(options, sink);
}

std::vector<std::string> phases_of(TabMode tabs, PageLayoutMode layout = PageLayoutMode::Fit) {
  RecordingSink sink;
  JobOptions options = sample_options();
  options.tabs = tabs;
  options.layout = layout;
  run_sample(options, sink);
  return sink.phases;
}

// The number in attribute `name`="..." of the SVG's metadata, or -1.
long svg_number(const std::string& svg, const std::string& name) {
  const std::string key = "data-" + name + "=\"";
  const std::size_t at = svg.find(key);
  return at == std::string::npos ? -1 : std::stol(svg.substr(at + key.size()));
}

std::ptrdiff_t position(const std::vector<std::string>& phases, const std::string& phase) {
  const auto it = std::find(phases.begin(), phases.end(), phase);
  return it == phases.end() ? -1 : it - phases.begin();
}

}  // namespace

TEST(PipelineRunner, ReportsTheTabPassBetweenUnfoldingAndWriting) {
  const std::vector<std::string> phases = phases_of(TabMode::Auto);
  std::string all;
  for (const std::string& p : phases) all += p + " ";
  SCOPED_TRACE(all);
  ASSERT_GE(position(phases, "validate"), 0);
  ASSERT_GE(position(phases, "tabs"), 0);
  ASSERT_GE(position(phases, "write"), 0);
  EXPECT_LT(position(phases, "load"), position(phases, "validate"));
  EXPECT_LT(position(phases, "validate"), position(phases, "tabs"));
  // Then the print: its layout (cut to fit, tabs, nesting), then the documents.
  EXPECT_EQ(position(phases, "tabs") + 1, position(phases, "layout"));
  EXPECT_EQ(position(phases, "layout") + 1, position(phases, "write"));
  EXPECT_EQ(phases.back(), "write");
}

// Tiled: the print's layout is no part of it (each fit search 10 s under ASan).
TEST(PipelineRunner, NoTabPassWithoutTabsOnTheNet) {
  for (TabMode mode : {TabMode::Strips, TabMode::None}) {
    const std::vector<std::string> phases = phases_of(mode, PageLayoutMode::Tile);
    EXPECT_EQ(position(phases, "tabs"), -1);
    EXPECT_EQ(phases.back(), "write");
  }
}

// The job's result metrics give the print's figures, the same as the SVG's metadata: a storefront
// sees how many glue strips a kit has without parsing the drawing.
TEST(PipelineRunner, ResultMetricsCountPagesTabsAndStrips) {
  for (TabMode mode : {TabMode::Auto, TabMode::Strips}) {
    RecordingSink sink;
    const JobOutput out = run_sample(mode, sink);
    const std::string& svg = out.files.at("net.svg").data;
    const auto& m = out.metrics;
    ASSERT_TRUE(m.contains("glue_tabs") && m.contains("glue_strips") && m.contains("cut_edges"))
        << m.dump();
    EXPECT_EQ(m["cut_edges"].get<long>(), svg_number(svg, "cut-edges"));
    EXPECT_EQ(m["glue_tabs"].get<long>(), svg_number(svg, "tabs"));
    EXPECT_EQ(m["glue_strips"].get<long>(), svg_number(svg, "strips"));
    EXPECT_GT(m["cut_edges"].get<long>(), 400);  // sample.obj: 1,000 faces
    EXPECT_EQ(m["glue_tabs"].get<long>() + m["glue_strips"].get<long>(),
              m["cut_edges"].get<long>());
    if (mode == TabMode::Strips)
      EXPECT_EQ(m["glue_tabs"].get<long>(), 0);
    else
      EXPECT_GT(m["glue_tabs"].get<long>(), 10 * m["glue_strips"].get<long>());
    EXPECT_GE(m["pages"].get<int>(), 1);
  }
}

// A job that asks for a low-poly version (simplify) unfolds and prints the collapsed mesh: an
// approximate result whose net JSON keeps the input's face count and measures the distance.
TEST(PipelineRunner, SimplifyMakesAnApproximateLowPolyResult) {
  JobOptions options = sample_options();
  options.detail = {DetailMode::Faces, 300};
  RecordingSink sink;
  const JobOutput out = run_sample(options, sink);
  EXPECT_TRUE(out.approximate);
  EXPECT_EQ(out.input_faces, 1000u);
  EXPECT_LE(out.faces, 300u);
  EXPECT_GE(out.faces, 250u);
  const auto net = nlohmann::json::parse(out.files.at("net.json").data);
  EXPECT_EQ(net["result"], "approximate");
  EXPECT_EQ(net["input"]["faces"], 1000);
  EXPECT_EQ(net["mesh"]["faces"].size(), out.faces);
  EXPECT_GT(out.metrics["hausdorff"].get<double>(), 0);
  EXPECT_LT(out.metrics["hausdorff"].get<double>(), 0.05);
  EXPECT_EQ(out.metrics["glue_tabs"].get<long>() + out.metrics["glue_strips"].get<long>(),
            out.metrics["cut_edges"].get<long>());
  EXPECT_NE(std::find(sink.phases.begin(), sink.phases.end(), "collapse"), sink.phases.end());
}
