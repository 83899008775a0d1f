/// \file reachability_workers.cpp
#include "reach_trajopt/ros/reachability_workers.h"

#include <algorithm>
#include <condition_variable>
#include <memory>
#include <thread>
#include <utility>

#include "reach_trajopt/CheckFootholds.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/async_service_call.h"
#include "reach_trajopt/ros/foothold_candidate_msgs.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {

FootholdCandidates part(const FootholdCandidates& batch, size_t begin, size_t end) {
  FootholdCandidates p = batch;
  p.candidates.assign(batch.candidates.begin() + begin, batch.candidates.begin() + end);
  return p;
}

}  // namespace

ReachabilityWorkerPool::ReachabilityWorkerPool(const ros::NodeHandle& nh,
                                               const std::vector<std::string>& services,
                                               double timeout_s, double retry_period_s, int nq,
                                               CandidateCheck in_process)
    : nh_(nh),
      timeout_s_(timeout_s),
      retry_period_s_(retry_period_s),
      nq_(nq),
      in_process_(std::move(in_process)) {
  if (!(timeout_s > 0.0)) throw ConfigError("~worker_timeout must be > 0 s");
  if (!(retry_period_s >= 0.0)) throw ConfigError("~worker_retry_period must be >= 0 s");
  if (!in_process_) throw ConfigError("ReachabilityWorkerPool: no in-process check");
  for (const std::string& s : services)
    workers_.push_back({std::make_shared<ServiceConnection<reach_trajopt::CheckFootholds>>(nh_, s),
                        ros::WallTime()});
  counts_.answered.assign(workers_.size(), 0);
}

ReachabilityWorkerPool::Counts ReachabilityWorkerPool::counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

std::vector<size_t> ReachabilityWorkerPool::availableWorkers() {
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::WallTime now = ros::WallTime::now();
  std::vector<size_t> available;
  for (size_t i = 0; i < workers_.size(); ++i)
    if (workers_[i].out_until <= now) available.push_back(i);
  return available;
}

bool ReachabilityWorkerPool::sendRound(const FootholdCandidates& batch,
                                       std::vector<Chunk>& chunks) {
  const std::vector<size_t> available = availableWorkers();
  if (available.empty()) return false;
  struct Call {
    size_t chunk, worker;
    uint64_t id;
    std::shared_ptr<PendingCall<reach_trajopt::CheckFootholds>> answer;
  };
  std::vector<Call> calls;
  for (size_t c = 0; c < chunks.size() && calls.size() < available.size(); ++c) {
    if (chunks[c].done) continue;
    uint64_t id;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      id = next_id_++;
    }
    const size_t w = available[calls.size()];
    calls.push_back({c, w, id,
                     workers_[w].connection->callAsync(toCheckFootholdsRequestMsg(
                         part(batch, chunks[c].begin, chunks[c].end), id))});
  }
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s_);
  for (const Call& call : calls) {
    Chunk& chunk = chunks[call.chunk];
    std::string failure;
    {
      const bool answered = call.answer->waitUntil(deadline);
      std::lock_guard<std::mutex> lock(call.answer->mutex);
      const reach_trajopt::CheckFootholds::Response& r = call.answer->response;
      if (!answered) {
        failure = "no answer within ~worker_timeout = " + std::to_string(timeout_s_) + " s";
      } else if (!call.answer->ok) {
        failure = "the call failed (the node is gone?)";
      } else if (!r.success) {
        failure = "rejected: " + r.message;
      } else if (r.request_id != call.id) {
        failure = "answered request " + std::to_string(r.request_id) + " for request " +
                  std::to_string(call.id);
      } else {
        try {
          chunk.outcomes = fromCheckFootholdsResponseMsg(r, chunk.end - chunk.begin, nq_);
          chunk.done = true;
        } catch (const ReachError& e) {
          failure = e.what();
        }
      }
    }
    std::lock_guard<std::mutex> lock(mutex_);
    Worker& worker = workers_[call.worker];
    if (failure.empty()) {
      ++counts_.answered[call.worker];
      continue;
    }
    ++counts_.failed;
    worker.connection->drop();  // a restarted worker is found again, a hung one not queued on
    worker.out_until = ros::WallTime::now() + ros::WallDuration(retry_period_s_);
    ROS_WARN(
        "reachability worker '%s' (request %lu): %s; left out for %.1f s, its %zu "
        "candidates go to another worker or this process",
        nh_.resolveName(worker.connection->service()).c_str(), static_cast<unsigned long>(call.id),
        failure.c_str(), retry_period_s_, chunk.end - chunk.begin);
  }
  return true;
}

std::vector<CandidateOutcome> ReachabilityWorkerPool::check(const FootholdCandidates& batch) {
  const size_t n = batch.candidates.size();
  const size_t parts =
      std::min(std::max<size_t>(availableWorkers().size(), 1), std::max<size_t>(n, 1));
  std::vector<Chunk> chunks(parts);
  for (size_t i = 0; i < parts; ++i) {
    chunks[i].begin = n * i / parts;
    chunks[i].end = n * (i + 1) / parts;
  }
  auto pending = [&] {
    return std::any_of(chunks.begin(), chunks.end(), [](const Chunk& c) { return !c.done; });
  };
  while (pending() && sendRound(batch, chunks)) {
  }
  std::vector<CandidateOutcome> outcomes;
  outcomes.reserve(n);
  for (Chunk& c : chunks) {
    if (!c.done) {
      c.outcomes = in_process_(part(batch, c.begin, c.end));
      if (c.outcomes.size() != c.end - c.begin)
        throw ReachError("ReachabilityWorkerPool: the in-process check answered " +
                         std::to_string(c.outcomes.size()) + " of " +
                         std::to_string(c.end - c.begin) + " candidates");
      std::lock_guard<std::mutex> lock(mutex_);
      ++counts_.in_process;
    }
    for (CandidateOutcome& o : c.outcomes) outcomes.push_back(std::move(o));
  }
  return outcomes;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
