#include "server/event_streams.h"

#include <vector>

#include "core/io/json_text.h"
#include "server/job_json.h"
#include "server/store_records.h"

namespace papernet::server {

using namespace std::chrono_literals;

EventStreams::EventStreams(JobService& service, std::size_t max_streams)
    : service_(service), max_streams_(max_streams), reader_([this] { run(); }) {}

EventStreams::~EventStreams() { stop(); }

std::shared_ptr<EventStreams::Watch> EventStreams::open(const std::string& id) {
  {
    std::lock_guard lock(mutex_);
    if (closing_ || open_ >= max_streams_) return nullptr;
    ++open_;
    ++jobs_[id].watchers;
  }
  return std::make_shared<Watch>(*this, id);
}

void EventStreams::close(const std::string& id) {
  std::lock_guard lock(mutex_);
  --open_;
  auto it = jobs_.find(id);
  if (it != jobs_.end() && --it->second.watchers == 0) jobs_.erase(it);
}

std::size_t EventStreams::open_count() const {
  std::lock_guard lock(mutex_);
  return open_;
}

EventStreams::State EventStreams::read(const std::string& id) {
  State state;
  const std::optional<JobView> view = service_.view(id);
  state.final = !view || is_final(view->record.status);
  state.doc = view ? json_text(job_to_json(*view, now_seconds())) : "null";
  return state;
}

void EventStreams::publish(const std::string& id, State state) {
  std::lock_guard lock(mutex_);
  auto it = jobs_.find(id);
  if (it == jobs_.end()) return;
  State& now = it->second.state;
  if (now.generation != 0 && now.doc == state.doc && now.final == state.final) return;
  now.doc = std::move(state.doc);
  now.final = state.final;
  now.generation = ++generations_;
}

EventStreams::State EventStreams::next(Watch& watch, std::uint64_t seen,
                                       std::chrono::milliseconds timeout) {
  const std::string& id = watch.id();
  bool unread = false;
  {
    std::lock_guard lock(mutex_);
    unread = jobs_.at(id).state.generation == 0;
  }
  if (unread) {  // a new stream's first event comes at once, not with the next change
    try {
      publish(id, read(id));
    } catch (const StoreError&) {  // the store is away for a moment: the reader tries again
    }
    changed_.notify_all();
  }
  std::unique_lock lock(mutex_);
  const Job& job = jobs_.at(id);
  changed_.wait_for(lock, timeout, [&] {
    return closing_ || (job.state.generation != 0 && job.state.generation != seen);
  });
  State state = job.state;
  state.closing = closing_;
  return state;
}

void EventStreams::run() {
  std::uint64_t version = 0;
  auto last_round = std::chrono::steady_clock::now();
  for (;;) {
    const std::uint64_t now_version = service_.wait_for_change(version, 100ms);
    std::vector<std::string> ids;
    bool closing = false;
    {
      std::lock_guard lock(mutex_);
      if (stop_) return;
      if (!service_.accepting()) closing_ = true;
      closing = closing_;
      for (const auto& entry : jobs_) ids.push_back(entry.first);
    }
    if (closing) changed_.notify_all();
    // A round when something changed, and every second anyway (a job's times move on).
    const auto now = std::chrono::steady_clock::now();
    if (!closing && (now_version != version || now - last_round >= 1s)) {
      version = now_version;
      last_round = now;
      for (const std::string& id : ids) {
        try {
          publish(id, read(id));
        } catch (const StoreError&) {  // the store is away for a moment: keep the streams
        }
      }
      changed_.notify_all();
    }
    // At most ten rounds a second, however often the unfolder reports.
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, 100ms, [&] { return stop_; });
    if (stop_) return;
  }
}

void EventStreams::stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = closing_ = true;
  }
  changed_.notify_all();
  if (reader_.joinable()) reader_.join();
}

}  // namespace papernet::server
