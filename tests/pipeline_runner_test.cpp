// The real job runner (server/pipeline_runner) driven directly, without queue or sockets: the
// phases it reports, in order, on a real mesh.
#include "server/pipeline_runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
  std::ifstream in(std::string(PAPERNET_TEST_DATA) + "/sample.obj", std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  JobInput input;
  input.mesh = s.str();
  input.format = MeshFormat::Obj;
  return input;
}

std::vector<std::string> phases_of(TabMode tabs) {
  JobOptions options;
  options.strategy = Strategy::TU;
  options.seed = 3;
  options.time_limit = 60;
  options.tabs = tabs;
  RecordingSink sink;
  const JobOutput out = make_pipeline_runner({})(sample_input(), options, sink);
  EXPECT_EQ(out.files.count("net.pdf"), 1u);
  return sink.phases;
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
  EXPECT_EQ(position(phases, "tabs") + 1, position(phases, "write")) << "tabs comes last but one";
  EXPECT_EQ(phases.back(), "write");
}

TEST(PipelineRunner, NoTabPassWithoutTabsOnTheNet) {
  for (TabMode mode : {TabMode::Strips, TabMode::None}) {
    const std::vector<std::string> phases = phases_of(mode);
    EXPECT_EQ(position(phases, "tabs"), -1);
    EXPECT_EQ(phases.back(), "write");
  }
}
