// The queue, workers and store of the job service, with injected runners (no geometry, no
// sockets): what happens to jobs, not what the unfolder computes.
#include "server/job_service.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <thread>

#include "core/errors.h"
#include "server/problem.h"
#include "tests/support/paths.h"
#include "tests/support/postgres.h"

using namespace papernet;
using namespace papernet::server;
using namespace std::chrono_literals;
using papernet::test::BothStores;

// The queue, the workers and the leases on both stores.
class JobServiceTest : public BothStores {};
INSTANTIATE_BOTH_STORES(JobServiceTest);

namespace {

std::string sample_mesh() {
  std::ifstream in(papernet::test::test_data_dir() + "/sample.obj", std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A runner that reports progress and an intermediate, then waits (polling cancellation like
// the unfolder does) until the test opens the gate.
struct Gate {
  std::atomic<bool> open{false};
  std::atomic<int> started{0};
};

JobRunner gated_runner(std::shared_ptr<Gate> gate) {
  return [gate](const JobInput& input, const JobOptions& options, JobSink& sink) {
    ++gate->started;
    ProgressInfo info;
    info.phase = "uncollapse";
    info.faces = 10;
    info.input_faces = 20;
    info.overlaps = 0;
    sink.report(info);
    JobOutput mid;
    mid.faces = 10;
    mid.input_faces = 20;
    mid.files["net.json"] = {"application/json", R"({"level":10})"};
    sink.intermediate(mid);
    while (!gate->open) {
      if (sink.cancelled()) throw CancelledException();
      std::this_thread::sleep_for(1ms);
    }
    JobOutput out;
    out.input_faces = 20;
    out.faces = 20;
    out.approximate = options.seed == 99;  // lets a test ask for an approximate result
    out.files["net.json"] = {"application/json",
                             "{\"bytes\":" + std::to_string(input.mesh.size()) + "}"};
    return out;
  };
}

JobInput input_of(std::string mesh) {
  JobInput in;
  in.mesh = std::move(mesh);
  in.format = MeshFormat::Obj;
  return in;
}

JobView wait_final(JobService& service, const std::string& id) {
  for (int i = 0; i < 500; ++i) {
    auto v = service.view(id);
    if (v && is_final(v->record.status)) return *v;
    std::this_thread::sleep_for(10ms);
  }
  ADD_FAILURE() << "job " << id << " did not finish";
  return *service.view(id);
}

void wait_running(JobService& service, const std::string& id) {
  for (int i = 0; i < 500; ++i) {
    if (service.view(id)->record.status == JobStatus::Running) return;
    std::this_thread::sleep_for(10ms);
  }
  ADD_FAILURE() << "job " << id << " did not start";
}

ServiceSettings settings(std::size_t workers, std::size_t queue) {
  ServiceSettings s;
  s.workers = workers;
  s.queue_length = queue;
  return s;
}

void quiet(const std::string&) {}

}  // namespace

TEST_P(JobServiceTest, JobRunsAndItsResultIsStored) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  gate->open = true;
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  const JobRecord job = service.submit(input_of(sample_mesh()), {});
  EXPECT_EQ(job.status, JobStatus::Queued);
  const JobView done = wait_final(service, job.id);
  EXPECT_EQ(done.record.status, JobStatus::Succeeded);
  EXPECT_EQ(done.record.faces, 20u);
  EXPECT_EQ(done.record.result_kind, "complete");
  const auto file = store.artifact(done.record.result_job, "net.json");
  ASSERT_TRUE(file);
  EXPECT_EQ(file->data, "{\"bytes\":" + std::to_string(sample_mesh().size()) + "}");
  EXPECT_EQ(done.result_files, std::vector<std::string>{"net.json"});
}

TEST_P(JobServiceTest, ApproximateResultIsReportedAsSuch) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  gate->open = true;
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  JobOptions options;
  options.seed = 99;
  const JobView done = wait_final(service, service.submit(input_of("v 0 0 0\n"), options).id);
  EXPECT_EQ(done.record.status, JobStatus::Approximated);
  EXPECT_EQ(done.record.result_kind, "approximate");
}

TEST_P(JobServiceTest, FullQueueRefusesWithRetryAfter) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  JobService service(store, gated_runner(gate), settings(1, 2), quiet);
  service.start();
  const JobRecord running = service.submit(input_of("v 1 0 0\n"), {});
  wait_running(service, running.id);
  const JobRecord second = service.submit(input_of("v 2 0 0\n"), {});
  const JobRecord third = service.submit(input_of("v 3 0 0\n"), {});
  EXPECT_EQ(service.view(second.id)->queue_position, 1u);
  EXPECT_EQ(service.view(third.id)->queue_position, 2u);
  try {
    service.submit(input_of("v 4 0 0\n"), {});
    ADD_FAILURE() << "a full queue accepted a job";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.problem().status, 429);
    EXPECT_EQ(e.problem().code, "queue_full");
    ASSERT_TRUE(e.problem().retry_after);
    EXPECT_GE(*e.problem().retry_after, 1);
  }
  EXPECT_EQ(service.stats().queued, 2u);
  gate->open = true;
  for (const auto& id : {running.id, second.id, third.id})
    EXPECT_EQ(wait_final(service, id).record.status, JobStatus::Succeeded);
}

TEST_P(JobServiceTest, RunningJobShowsProgressAndIntermediate) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  const JobRecord job = service.submit(input_of("v 0 0 0\n"), {});
  wait_running(service, job.id);
  for (int i = 0; i < 200 && !service.view(job.id)->intermediate; ++i)
    std::this_thread::sleep_for(5ms);
  const JobView v = *service.view(job.id);
  ASSERT_TRUE(v.progress);
  EXPECT_EQ(v.progress->phase, "uncollapse");
  EXPECT_EQ(v.progress->input_faces, 20u);
  ASSERT_TRUE(v.intermediate);
  EXPECT_EQ(v.intermediate->files, std::vector<std::string>{"net.json"});
  EXPECT_EQ(service.intermediate(job.id, "net.json")->file.data, R"({"level":10})");
  gate->open = true;
  wait_final(service, job.id);
}

TEST_P(JobServiceTest, CancelQueuedAndRunningJobs) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  const JobRecord running = service.submit(input_of("v 1 0 0\n"), {});
  const JobRecord queued = service.submit(input_of("v 2 0 0\n"), {});
  wait_running(service, running.id);

  EXPECT_EQ(service.cancel(queued.id).record.status, JobStatus::Cancelled);
  const auto before = std::chrono::steady_clock::now();
  service.cancel(running.id);
  EXPECT_EQ(wait_final(service, running.id).record.status, JobStatus::Cancelled);
  EXPECT_LT(std::chrono::steady_clock::now() - before, 1s);
  EXPECT_EQ(gate->started, 1);  // the cancelled queued job never ran

  try {
    service.cancel(new_job_id());
    ADD_FAILURE() << "cancelled an unknown job";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.problem().code, "job_not_found");
  }
}

TEST_P(JobServiceTest, CancelFinishedJobIsAConflict) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  gate->open = true;
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  const std::string id = service.submit(input_of("v 0 0 0\n"), {}).id;
  wait_final(service, id);
  try {
    service.cancel(id);
    ADD_FAILURE() << "cancelled a finished job";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.problem().status, 409);
  }
}

TEST_P(JobServiceTest, OverrunningJobFailsWithTimeLimitExceeded) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();  // never opened: the runner would wait forever
  ServiceSettings s = settings(1, 4);
  s.hard_time_grace = 0.05;
  JobService service(store, gated_runner(gate), s, quiet);
  service.start();
  JobOptions options;
  options.time_limit = 0.1;
  const JobView done = wait_final(service, service.submit(input_of("v 0 0 0\n"), options).id);
  EXPECT_EQ(done.record.status, JobStatus::Failed);
  EXPECT_EQ(done.record.error["code"], "time_limit_exceeded");
}

TEST_P(JobServiceTest, RunnerErrorsBecomeStoredProblems) {
  const auto owned = open_store();
  JobStore& store = *owned;
  JobService service(
      store,
      [](const JobInput&, const JobOptions&, JobSink&) -> JobOutput {
        throw InvalidInputException("edge (3, 4) has 3 faces: not manifold");
      },
      settings(1, 4), quiet);
  service.start();
  const JobView done = wait_final(service, service.submit(input_of("v 0 0 0\n"), {}).id);
  EXPECT_EQ(done.record.status, JobStatus::Failed);
  EXPECT_EQ(done.record.error["status"], 422);
  EXPECT_EQ(done.record.error["code"], "invalid_mesh");
  EXPECT_EQ(done.record.error["detail"], "edge (3, 4) has 3 faces: not manifold");
}

TEST_P(JobServiceTest, IdenticalInputIsAnsweredFromTheStoredResult) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  gate->open = true;
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  const std::string first = service.submit(input_of(sample_mesh()), {}).id;
  wait_final(service, first);
  const JobRecord again = service.submit(input_of(sample_mesh()), {});
  EXPECT_EQ(again.status, JobStatus::Succeeded);
  EXPECT_EQ(again.result_job, first);
  EXPECT_EQ(gate->started, 1);
  JobOptions other;
  other.seed = 2;
  const JobRecord different = service.submit(input_of(sample_mesh()), other);
  EXPECT_EQ(different.status, JobStatus::Queued);
  wait_final(service, different.id);
  EXPECT_EQ(gate->started, 2);
}

TEST_P(JobServiceTest, ShutdownRequeuesRunningJobsAndRefusesNewOnes) {
  const auto owned = open_store();
  JobStore& store = *owned;
  auto gate = std::make_shared<Gate>();
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  const std::string id = service.submit(input_of("v 0 0 0\n"), {}).id;
  wait_running(service, id);
  service.shutdown(50ms);
  EXPECT_EQ(store.find(id)->status, JobStatus::Queued);
  EXPECT_FALSE(service.accepting());
  try {
    service.submit(input_of("v 1 0 0\n"), {});
    ADD_FAILURE() << "accepted a job while shutting down";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.problem().status, 503);
  }
}

// What a kill -9 leaves behind: a finished job, a job a dead node was running, a queued one.
// A new service on the same store runs the last two and leaves the first alone.
TEST_P(JobServiceTest, RestartRunsQueuedAndInterruptedJobs) {
  std::vector<std::string> ids;
  {
    const auto store = open_store();
    for (int i = 0; i < 3; ++i) {
      JobRecord job;
      job.id = new_job_id();
      job.created = now_seconds();
      job.options = options_to_json({});
      job.format = "obj";
      job.input_key = "k" + std::to_string(i);
      const JobInput in = input_of(sample_mesh() + std::string(i, '\n'));
      ASSERT_TRUE(store->insert(job, &in, 10));
      ids.push_back(job.id);
    }
    // The dead node finished the first and was running the second (under a lease of 0 s: it
    // expired as the node died).
    JobRecord done = store->claim("dead-node", 3600, now_seconds())->record;
    EXPECT_EQ(done.id, ids[0]);
    done.status = JobStatus::Succeeded;
    done.finished = now_seconds();
    done.result_kind = "complete";
    done.result_job = done.id;
    JobOutput out;
    out.files["net.json"] = {"application/json", "{\"kept\":true}"};
    ASSERT_TRUE(store->finish(done, {"dead-node", 1}, &out));
    EXPECT_EQ(store->claim("dead-node", 0, now_seconds())->record.id, ids[1]);
  }
  const auto owned = open_store();
  JobStore& store = *owned;
  EXPECT_EQ(store.count_by_status()["running"], 1u);
  EXPECT_EQ(store.count_by_status()["queued"], 1u);
  auto gate = std::make_shared<Gate>();
  gate->open = true;
  {
    JobService service(store, gated_runner(gate), settings(2, 4), quiet);
    service.start();
    const JobView interrupted = wait_final(service, ids[1]);
    EXPECT_EQ(interrupted.record.status, JobStatus::Succeeded);
    EXPECT_EQ(interrupted.record.attempts, 2);
    EXPECT_EQ(wait_final(service, ids[2]).record.status, JobStatus::Succeeded);
    EXPECT_EQ(service.stats().lease_expiries, postgres() ? 1u : 0u)
        << "PostgreSQL takes the job over when its lease expires; SQLite requeues it at start";
  }
  EXPECT_EQ(gate->started, 2);
  EXPECT_EQ(store.artifact(ids[0], "net.json")->data, "{\"kept\":true}");
  EXPECT_EQ(store.count_by_status()["succeeded"], 3u);
}

// A job whose node died each time it ran it (here: claims under leases that expire at once)
// fails once it has used up its attempts, without running again.
TEST_P(JobServiceTest, JobThatKeepsKillingTheServerFails) {
  const auto owned = open_store();
  JobStore& store = *owned;
  JobRecord job;
  job.id = new_job_id();
  job.options = options_to_json({});
  job.format = "obj";
  const JobInput in = input_of("v 0 0 0\n");
  store.insert(job, &in, 10);
  for (int i = 0; i < 3; ++i) {  // three crashes
    ASSERT_TRUE(store.claim("crashing-node", 0, now_seconds()));
    store.recover_interrupted();
  }
  auto gate = std::make_shared<Gate>();
  gate->open = true;
  JobService service(store, gated_runner(gate), settings(1, 4), quiet);
  service.start();
  const JobView v = wait_final(service, job.id);
  EXPECT_EQ(v.record.status, JobStatus::Failed);
  EXPECT_EQ(v.record.error["code"], "interrupted_too_often");
  EXPECT_EQ(v.record.attempts, 4);
  EXPECT_EQ(gate->started, 0);
}

TEST(JobIdTest, OpaqueAndValidated) {
  const std::string id = new_job_id();
  EXPECT_TRUE(valid_job_id(id));
  EXPECT_NE(id, new_job_id());
  EXPECT_FALSE(valid_job_id("../../etc/passwd"));
  EXPECT_FALSE(valid_job_id(id.substr(1)));
  EXPECT_FALSE(valid_job_id(std::string(32, 'G')));
}
