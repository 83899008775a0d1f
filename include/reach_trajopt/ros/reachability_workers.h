#pragma once
/// \file reachability_workers.h
/// @brief The reachability workers of a node: N reachability_nodes (each its own name or
/// namespace, on this machine or others) serving check_footholds (reach_trajopt/CheckFootholds).
/// A batch of candidate footholds (one ring of the nearest-feasible-foothold search) is split
/// into one contiguous chunk per available worker; the chunks are sent in parallel (a thread
/// each) and their answers collected by request id. A worker whose call fails (a dead node), is
/// rejected, malformed or not answered within the timeout (a hung node) is noticed: it is left
/// out for `retry_period` and its chunk goes to another available worker, or, with none left,
/// to the in-process check. The merged outcomes are those of the in-process search whichever
/// worker answered (every number float64 as computed).

#include <ros/ros.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "reach_trajopt/CheckFootholds.h"
#include "reach_trajopt/planner/nearest_feasible_foothold.h"
#include "reach_trajopt/ros/async_service_call.h"

namespace reach_trajopt {
namespace ros_bridge {

class ReachabilityWorkerPool {
 public:
  /// \param services   the workers' check_footholds services (names resolved in `nh`)
  /// \param timeout_s  [s wall] longest wait for a chunk's answer, > 0
  /// \param retry_period_s  [s wall] how long a failed worker is left out, >= 0
  /// \param nq         the model's coordinates (sizes of the answers)
  /// \param in_process checks a chunk here when no worker is left (every candidate)
  /// \throws ConfigError on a bad timeout or retry period.
  ReachabilityWorkerPool(const ros::NodeHandle& nh, const std::vector<std::string>& services,
                         double timeout_s, double retry_period_s, int nq,
                         CandidateCheck in_process);

  /// Every candidate of `batch` checked, in order (see the file comment). Thread-safe.
  std::vector<CandidateOutcome> check(const FootholdCandidates& batch);

  /// How the chunks were answered so far (for logs and tests).
  struct Counts {
    std::vector<uint64_t> answered;  ///< chunks answered per worker
    uint64_t failed = 0;             ///< calls that failed, were rejected or timed out
    uint64_t in_process = 0;         ///< chunks checked in this process
  };
  Counts counts() const;

 private:
  struct Worker {
    std::shared_ptr<ServiceConnection<reach_trajopt::CheckFootholds>> connection;
    ros::WallTime out_until;  ///< left out before this time (after a failure)
  };
  struct Chunk {
    size_t begin = 0, end = 0;  ///< candidates [begin, end) of the batch
    std::vector<CandidateOutcome> outcomes;
    bool done = false;
  };
  /// Indices of the workers not left out now.
  std::vector<size_t> availableWorkers();
  /// Sends each chunk of `chunks` that is not done to a distinct available worker (as many as
  /// there are), waits for all, marks the failed workers; returns false if none was available.
  bool sendRound(const FootholdCandidates& batch, std::vector<Chunk>& chunks);

  ros::NodeHandle nh_;
  std::vector<Worker> workers_;
  double timeout_s_, retry_period_s_;
  int nq_;
  CandidateCheck in_process_;
  mutable std::mutex mutex_;  ///< guards workers_[].out_until, next_id_, counts_
  uint64_t next_id_ = 1;
  Counts counts_;
};

}  // namespace ros_bridge
}  // namespace reach_trajopt
