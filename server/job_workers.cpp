// The service's workers (docs/scaling.md): each claims the oldest claimable job from the store,
// runs it, and stores its end under its claim; the lease keeper renews the leases of the jobs
// running here, publishes their progress and intermediates to the store for other nodes, and
// learns of cancellations and of leases lost to another node.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/io/json_text.h"
#include "server/internal/live_job.h"
#include "server/job_service.h"
#include "server/problem.h"

namespace papernet::server {
namespace {

using namespace std::chrono_literals;

// How often an idle worker looks for claimable jobs (expired leases are not announced), and
// how often the lease keeper renews leases and publishes progress.
constexpr auto kClaimPoll = 1s;
constexpr auto kLeaseTick = 200ms;

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", seconds);
  return text;
}

}  // namespace

// The hook a running job talks to. Cancellation: the client's DELETE (on any node), the hard
// time limit, a lease lost to another node, or a shutdown that outlived its grace period.
class JobService::Sink : public JobSink {
 public:
  Sink(JobService& service, std::shared_ptr<Live> live, double deadline)
      : service_(service), live_(std::move(live)), deadline_(deadline) {}

  void report(const ProgressInfo& info) override {
    std::lock_guard lock(service_.mutex_);
    live_->progress = info;
    live_->progress_published = false;
    ++service_.version_;
    service_.change_cv_.notify_all();
  }
  void intermediate(JobOutput output) override {
    auto shared = std::make_shared<const JobOutput>(std::move(output));
    std::lock_guard lock(service_.mutex_);
    live_->intermediate = std::move(shared);
    live_->intermediate_published = false;
    ++service_.version_;
    service_.change_cv_.notify_all();
  }
  bool cancelled() override {
    if (live_->cancel || live_->lost || service_.abort_running_) return true;
    if (now_seconds() > deadline_) timed_out_ = true;
    return timed_out_;
  }
  bool timed_out() const { return timed_out_; }

 private:
  JobService& service_;
  std::shared_ptr<Live> live_;
  double deadline_;
  bool timed_out_ = false;
};

void JobService::start() {
  for (const std::string& id : store_.recover_interrupted())
    log_("job " + id + " running -> queued (recovered)");
  store_.listen([this](const StoreEvent& event) { on_store_event(event); });
  char lease[32];
  std::snprintf(lease, sizeof lease, "%g s", settings_.lease_seconds);
  log_("node " + settings_.node + ": " + store_.kind() + " store, " +
       std::to_string(settings_.workers) + " workers, leases of " + lease);
  for (std::size_t i = 0; i < settings_.workers; ++i) workers_.emplace_back([this] { work(); });
  keeper_ = std::thread([this] { keep_leases(); });
}

void JobService::on_store_event(const StoreEvent& event) {
  std::lock_guard lock(mutex_);
  if (event.kind == StoreEvent::Kind::Queued) {
    ++wakeups_;
    work_cv_.notify_all();
    return;
  }
  if (event.kind == StoreEvent::Kind::Cancel)
    if (auto it = live_.find(event.job_id); it != live_.end()) it->second->cancel = true;
  ++version_;
  change_cv_.notify_all();
}

void JobService::work() {
  bool store_failing = false;
  for (;;) {
    std::uint64_t seen = 0;
    {
      std::lock_guard lock(mutex_);
      if (stop_ || draining_) return;
      seen = wakeups_;
    }
    std::optional<ClaimedJob> claimed;
    try {
      claimed = store_.claim(settings_.node, settings_.lease_seconds, now_seconds());
      store_failing = false;
    } catch (const std::exception& e) {
      if (!store_failing) log_(std::string("worker: cannot claim jobs: ") + e.what());
      store_failing = true;
    }
    if (claimed) {
      run_one(std::move(*claimed));
      continue;
    }
    std::unique_lock lock(mutex_);
    work_cv_.wait_for(lock, kClaimPoll, [&] { return stop_ || draining_ || wakeups_ != seen; });
  }
}

void JobService::run_one(ClaimedJob claimed) {
  JobRecord record = std::move(claimed.record);
  const std::string id = record.id;
  const Claim claim{settings_.node, record.attempts};
  auto live = std::make_shared<Live>(claim);
  bool draining = false;
  {
    std::lock_guard lock(mutex_);
    ++claims_;
    if (!claimed.expired_node.empty()) ++lease_expiries_;
    draining = draining_;
    if (!draining) live_[id] = live;
    ++version_;
  }
  change_cv_.notify_all();
  if (draining) {  // claimed while the shutdown began: back in the queue, said as for a run
    try {
      if (store_.release(id, claim)) log_("job " + id + " running -> queued (server stopping)");
    } catch (const StoreError& e) {
      log_("job " + id + " could not be put back in the queue: " + e.what());
    }
    return;
  }
  log_("job " + id +
       (claimed.expired_node.empty()
            ? " queued -> running"
            : " running -> running (the lease of " + claimed.expired_node + " expired)") +
       " (attempt " + std::to_string(record.attempts) + ")");
  const auto end_with = [&](JobStatus status, const Problem& problem) {
    record.finished = now_seconds();
    finish(record, claim, status, nullptr, problem_json(problem));
  };
  if (record.cancel_requested)
    return end_with(JobStatus::Cancelled, make_problem("job_cancelled", "cancelled while running"));
  if (record.attempts > settings_.max_attempts)
    return end_with(JobStatus::Failed,
                    make_problem("interrupted_too_often",
                                 "the job was started " + std::to_string(record.attempts - 1) +
                                     " times and its node stopped or crashed each time (at most " +
                                     std::to_string(settings_.max_attempts) + " attempts)"));
  JobOptions options;
  JobInput input;
  try {
    options = parse_options_json(json_text(record.options), settings_.options_limits);
    input = store_.input(id);
  } catch (const StoreUnavailable& e) {
    log_("job " + id + " cannot be read now (" + e.what() + "); its lease will expire");
    return forget(id);
  } catch (...) {
    return end_with(JobStatus::Failed, problem_from_exception(std::current_exception()));
  }
  const double limit = options.time_limit.value_or(settings_.default_time_limit);
  Sink sink(*this, live, record.started + limit + settings_.hard_time_grace);
  try {
    JobOutput output = runner_(input, options, sink);
    record.finished = now_seconds();
    record.input_faces = output.input_faces;
    record.faces = output.faces;
    record.overlaps = output.overlaps;
    record.metrics = output.metrics;
    record.result_kind = output.approximate ? "approximate" : "complete";
    record.result_job = record.id;
    finish(record, claim, output.approximate ? JobStatus::Approximated : JobStatus::Succeeded,
           &output, nullptr);
  } catch (...) {
    record.finished = now_seconds();
    {
      std::lock_guard lock(mutex_);
      if (live->progress) record.input_faces = live->progress->input_faces;
    }
    if (live->lost) {
      log_("job " + id + " stopped here: its lease passed to another node");
      return forget(id);
    }
    if (abort_running_ && !live->cancel) {
      try {
        if (store_.release(id, claim)) log_("job " + id + " running -> queued (server stopping)");
      } catch (const StoreError& e) {
        log_("job " + id + " could not be put back in the queue (" + e.what() +
             "); its lease will expire");
      }
      return forget(id);
    }
    if (live->cancel)
      return end_with(JobStatus::Cancelled,
                      make_problem("job_cancelled", "cancelled while running"));
    if (sink.timed_out())
      return end_with(
          JobStatus::Failed,
          make_problem("time_limit_exceeded", "the job did not finish within its time limit of " +
                                                  std::to_string(limit) + " seconds"));
    end_with(JobStatus::Failed, problem_from_exception(std::current_exception()));
  }
}

void JobService::forget(const std::string& id) {
  {
    std::lock_guard lock(mutex_);
    live_.erase(id);
    ++version_;
  }
  change_cv_.notify_all();
}

bool JobService::finish(JobRecord& record, const Claim& claim, JobStatus status,
                        const JobOutput* output, const nlohmann::json& error) {
  const JobStatus before = record.status;
  record.status = status;
  record.error = error;
  bool stored = false;
  bool waiting_logged = false;
  for (auto backoff = 100ms;;) {
    try {
      stored = store_.finish(record, claim, output);
      if (!stored) {  // a repetition after a lost connection finds its own first write
        const auto now = store_.find(record.id);
        stored = now && now->status == record.status && now->node == claim.node &&
                 now->attempts == claim.attempt;
      }
      break;
    } catch (const StoreUnavailable& e) {
      std::shared_ptr<Live> live;
      {
        std::lock_guard lock(mutex_);
        if (auto it = live_.find(record.id); it != live_.end()) live = it->second;
      }
      if (abort_running_ || !live || live->lost) {
        log_("job " + record.id + " ended but could not be stored (" + e.what() +
             "); its lease will expire");
        forget(record.id);
        return false;
      }
      if (!waiting_logged) log_("job " + record.id + " ended; storing it when the store is back");
      waiting_logged = true;
      std::this_thread::sleep_for(backoff);
      backoff = std::min<std::chrono::milliseconds>(backoff * 2, 2s);
    } catch (const StoreError& e) {
      if (!output) {
        log_("job " + record.id + " ended but could not be stored: " + e.what());
        forget(record.id);
        return false;
      }
      // The result does not fit (a full disk, a statement timeout): the job fails, saying why.
      output = nullptr;
      record.status = status = JobStatus::Failed;
      record.result_kind.clear();
      record.result_job.clear();
      record.error = problem_json(
          make_problem("store_failed", std::string("the result could not be stored: ") + e.what()));
    }
  }
  const double seconds = record.started > 0 ? record.finished - record.started : 0;
  bool counted_loss = false;
  {
    std::lock_guard lock(mutex_);
    if (auto it = live_.find(record.id); !stored && it != live_.end())
      counted_loss = !it->second->lost.exchange(true);
    if (counted_loss) ++leases_lost_;
    live_.erase(record.id);
    ++version_;
    if (stored) {
      for (std::size_t i = 0; i < buckets_.size(); ++i)
        if (seconds <= buckets_[i]) ++bucket_counts_[i];
      ++bucket_counts_.back();
      duration_sum_ += seconds;
      ++duration_count_;
    }
  }
  change_cv_.notify_all();
  if (!stored) {
    log_("job " + record.id +
         " ended here, but its lease had passed to another node; this end "
         "is dropped");
    return false;
  }
  std::string line = "job " + record.id + " " + status_name(before) + " -> " + status_name(status) +
                     " after " + seconds_text(seconds);
  if (record.error.is_object())
    line += " (" + record.error.value("code", "") + ": " + record.error.value("detail", "") + ")";
  log_(line);
  return true;
}

// Retention, on the lease keeper's thread: every node sweeps (JobStore::expire is idempotent).
void JobService::sweep(std::chrono::steady_clock::time_point& next) {
  const auto now = std::chrono::steady_clock::now();
  const bool timed = settings_.retention_seconds > 0, bounded = settings_.max_store_bytes > 0;
  if ((!timed && !bounded) || now < next) return;
  double every = timed ? std::clamp(settings_.retention_seconds / 2, 0.2, 60.0) : 60.0;
  if (bounded) every = std::min(every, 2.0);
  next = now + std::chrono::milliseconds(static_cast<long>(every * 1000));
  const double wall = now_seconds();
  const double keys_before = wall - 24 * 3600.0;
  try {
    if (timed) {
      const std::size_t expired = store_.expire(wall - settings_.retention_seconds, keys_before);
      if (expired > 0)
        log_("retention: " + std::to_string(expired) +
             " finished jobs expired; their files removed");
    }
    std::uint64_t bytes = bounded ? store_.stored_bytes() : 0;
    if (bytes > settings_.max_store_bytes) {
      // The store's size bound: the jobs that finished first go first, each round at least one.
      const std::uint64_t before = bytes;
      std::size_t expired = 0;
      while (bytes > settings_.max_store_bytes) {
        const std::optional<double> oldest = store_.oldest_finished();
        if (!oldest) break;  // only queued and running jobs hold files
        expired += store_.expire(std::nextafter(*oldest, HUGE_VAL), keys_before);
        bytes = store_.stored_bytes();
      }
      log_("retention: the store held " + std::to_string(before) + " bytes, more than " +
           std::to_string(settings_.max_store_bytes) + " (--max-store); " +
           std::to_string(expired) + " finished jobs expired early, " + std::to_string(bytes) +
           " bytes left");
    }
  } catch (const std::exception& e) {
    log_(std::string("retention: ") + e.what());
  }
}

void JobService::keep_leases() {
  struct Beat {
    std::string id;
    std::shared_ptr<Live> live;
    std::optional<nlohmann::json> progress;
    std::shared_ptr<const JobOutput> intermediate;
  };
  bool failing = false;
  auto next_sweep = std::chrono::steady_clock::now();
  std::unique_lock lock(mutex_);
  while (!keeper_cv_.wait_for(lock, kLeaseTick, [&] { return keeper_stop_; })) {
    std::vector<Beat> beats;
    for (auto& [id, live] : live_) {
      Beat beat{id, live, std::nullopt, nullptr};
      if (!live->progress_published && live->progress)
        beat.progress = progress_to_json(*live->progress);
      if (!live->intermediate_published) beat.intermediate = live->intermediate;
      live->progress_published = live->intermediate_published = true;
      beats.push_back(std::move(beat));
    }
    lock.unlock();
    sweep(next_sweep);
    for (const Beat& beat : beats) {
      const Claim& claim = beat.live->claim;
      try {
        const LeaseState state = store_.renew(beat.id, claim, settings_.lease_seconds,
                                              beat.progress ? &*beat.progress : nullptr);
        if (state.cancel_requested) beat.live->cancel = true;
        if (beat.intermediate && state.held)
          store_.put_intermediate(beat.id, claim, *beat.intermediate);
        failing = false;
        if (state.held) continue;
        // Not held: another node claimed it, unless it just ended here.
        const auto now = store_.find(beat.id);
        if (now && now->node == claim.node && now->attempts == claim.attempt) continue;
        if (!beat.live->lost.exchange(true)) {
          log_("job " + beat.id + ": its lease passed to another node; stopping it here");
          std::lock_guard relock(mutex_);
          ++leases_lost_;
        }
      } catch (const std::exception& e) {
        // Publish again at the next tick what did not get through.
        std::lock_guard relock(mutex_);
        if (beat.progress) beat.live->progress_published = false;
        if (beat.intermediate) beat.live->intermediate_published = false;
        if (!failing) log_(std::string("lease keeper: ") + e.what());
        failing = true;
      }
    }
    lock.lock();
  }
}

}  // namespace papernet::server
