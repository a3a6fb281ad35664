#include "server/job_json.h"

#include <gtest/gtest.h>

#include <optional>

#include "server/job.h"
#include "server/problem.h"

using namespace papernet::server;

namespace {

JobView queued_view() {
  JobView v;
  v.record.id = new_job_id();
  v.record.status = JobStatus::Queued;
  v.record.created = 1'700'000'000.25;
  v.record.format = "obj";
  v.record.input_bytes = 123;
  v.queue_position = 3;
  return v;
}

}  // namespace

TEST(JobJsonTest, QueuedJobShowsItsPlaceAndNoResult) {
  const nlohmann::json doc = job_to_json(queued_view(), 1'700'000'010);
  EXPECT_EQ(doc["status"], "queued");
  EXPECT_EQ(doc["progress"]["queue_position"], 3);
  EXPECT_EQ(doc["progress"]["elapsed_seconds"], 0.0);
  EXPECT_EQ(doc["progress"]["fraction"], 0.0);
  EXPECT_TRUE(doc["result"].is_null());
  EXPECT_TRUE(doc["error"].is_null());
  EXPECT_EQ(doc["created"], "2023-11-14T22:13:20.250Z");
  EXPECT_FALSE(doc["links"].contains("net.json"));
  EXPECT_EQ(doc["links"]["events"], "/v1/jobs/" + doc["id"].get<std::string>() + "/events");
}

TEST(JobJsonTest, RunningJobShowsProgressAndIntermediateLinks) {
  JobView v = queued_view();
  v.record.status = JobStatus::Running;
  v.record.started = 1'700'000'001;
  v.queue_position = 0;
  v.progress = papernet::ProgressInfo{"uncollapse", 800, 2000, 0, 17, 4.5};
  v.progress->fraction = 0.1239;
  v.intermediate = IntermediateLevel{800, 2000, 0, {"net.json"}};
  const nlohmann::json doc = job_to_json(v, 1'700'000'003);
  EXPECT_EQ(doc["progress"]["phase"], "uncollapse");
  EXPECT_EQ(doc["progress"]["fraction"], 0.123);  // rounded down: 1 only once the job ended
  EXPECT_EQ(doc["progress"]["faces"], 800);
  // The run has written its last document, but the job has not stored its results yet.
  v.progress->fraction = 1;
  EXPECT_EQ(job_to_json(v, 1'700'000'003)["progress"]["fraction"], 0.999);
  EXPECT_EQ(doc["progress"]["input_faces"], 2000);
  EXPECT_EQ(doc["progress"]["elapsed_seconds"], 2.0);
  EXPECT_TRUE(doc["progress"]["queue_position"].is_null());
  EXPECT_EQ(doc["input"]["faces"], 2000);
  EXPECT_EQ(doc["intermediate"]["faces"], 800);
  EXPECT_TRUE(doc["links"].contains("net.json"));
  EXPECT_FALSE(doc["links"].contains("net.pdf"));
}

// What a node publishes of a running job for the others (the store) keeps its piece and fraction.
TEST(JobJsonTest, PublishedProgressKeepsPieceAndFraction) {
  papernet::ProgressInfo info{"tabs", 500, 2000, 0, 40, 3.0};
  info.piece = 2;
  info.pieces = 3;
  info.fraction = 0.5;
  const std::optional<papernet::ProgressInfo> back = progress_from_json(progress_to_json(info));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->phase, "tabs");
  EXPECT_EQ(back->piece, 2u);
  EXPECT_EQ(back->pieces, 3u);
  EXPECT_EQ(back->fraction, 0.5);
}

TEST(JobJsonTest, FinishedJobsShowResultOrError) {
  JobView ok = queued_view();
  ok.queue_position = 0;
  ok.record.status = JobStatus::Approximated;
  ok.record.started = 1'700'000'001;
  ok.record.finished = 1'700'000'002.5;
  ok.record.result_kind = "approximate";
  ok.record.faces = 900;
  ok.record.input_faces = 2000;
  ok.result_files = {"mesh.glb", "net.json"};
  const nlohmann::json done = job_to_json(ok, 1'700'000'100);
  EXPECT_EQ(done["result"]["kind"], "approximate");
  EXPECT_EQ(done["progress"]["elapsed_seconds"], 1.5);
  EXPECT_EQ(done["progress"]["fraction"], 1.0);
  EXPECT_TRUE(done["links"].contains("mesh.glb"));
  EXPECT_FALSE(done["links"].contains("net.svg"));

  JobView failed = queued_view();
  failed.queue_position = 0;
  failed.record.status = JobStatus::Failed;
  failed.record.error = problem_json(make_problem("invalid_mesh", "2 non-manifold edges"));
  const nlohmann::json doc = job_to_json(failed, 1'700'000'100);
  EXPECT_EQ(doc["error"]["code"], "invalid_mesh");
  EXPECT_EQ(doc["error"]["status"], 422);
  EXPECT_TRUE(doc["result"].is_null());
}

// A result file saved from a browser or by `curl -OJ` is named after the kit's title where the
// job has one, else after the file; a page gets its extension, which its URL lacks.
TEST(JobJsonTest, ResultFilesAreNamedAfterTheKit) {
  const nlohmann::json untitled = {{"title", nullptr}, {"paper", "A4"}},
                       duck = {{"title", "Kitchen Duck"}};
  struct Case {
    nlohmann::json options;
    std::string file, content_type, disposition;
  };
  const Case cases[] = {
      {untitled, "net.pdf", "application/pdf", "inline; filename=\"net.pdf\""},
      {untitled, page_file_name(2), "image/svg+xml", "inline; filename=\"page-2.svg\""},
      {untitled, texture_file_name(0), "image/png", "inline; filename=\"texture-0.png\""},
      {duck, "net.pdf", "application/pdf", "inline; filename=\"Kitchen Duck.pdf\""},
      {duck, "mesh.glb", "model/gltf-binary", "inline; filename=\"Kitchen Duck.glb\""},
      {duck, page_file_name(12), "image/svg+xml",
       "inline; filename=\"Kitchen Duck - page 12.svg\""},
      {duck, texture_file_name(1), "image/jpeg",
       "inline; filename=\"Kitchen Duck - texture-1.jpg\""},
      // Characters no file system takes in a name, a quote among them, and a leading dot: "_".
      {{{"title", ".a/b\\c:\"d\"?"}},
       "net.svg",
       "image/svg+xml",
       "inline; filename=\"_a_b_c__d__.svg\""},
      // Outside ASCII: "_" per letter in filename, the UTF-8 bytes in filename*.
      {{{"title", "Ente f\u00fcr L\u00fcneburg"}},
       "net.pdf",
       "application/pdf",
       "inline; filename=\"Ente f_r L_neburg.pdf\"; "
       "filename*=UTF-8''Ente%20f%C3%BCr%20L%C3%BCneburg.pdf"},
  };
  for (const Case& c : cases)
    EXPECT_EQ(content_disposition(c.options, c.file, c.content_type), c.disposition) << c.file;
}
