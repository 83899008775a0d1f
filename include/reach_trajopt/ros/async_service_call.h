#pragma once
/// \file async_service_call.h
/// A ROS service call with a deadline. ros::ServiceClient::call has no timeout: a hung node
/// (stopped, deadlocked, not dead) blocks its caller for ever. callAsync() makes the call on a
/// thread of its own (detached, it owns its state: it stays blocked until that node dies) and
/// the caller waits with a deadline instead (PendingCall::waitUntil).
///
/// ServiceConnection keeps one persistent connection per service: a non-persistent
/// ros::ServiceClient asks the master for the service and opens a TCP connection on every call
/// (3-4 calls per walking step); a persistent one does that once. A connection whose call
/// failed or timed out is dropped, so a restarted or replaced node is found again on the next
/// call, and a hung one never blocks a later call behind its stuck one.

#include <ros/ros.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

namespace reach_trajopt {
namespace ros_bridge {

/// The answer of one call, filled by the thread that makes it.
template <class Service>
struct PendingCall {
  std::mutex mutex;
  std::condition_variable answered;
  bool done = false;
  bool ok = false;  ///< the call returned true
  typename Service::Response response;

  /// Waits until the call returns or `deadline` (wall time) passes; true when it returned.
  bool waitUntil(const ros::WallTime& deadline) {
    std::unique_lock<std::mutex> lock(mutex);
    while (!done && ros::WallTime::now() < deadline)
      answered.wait_for(lock, std::chrono::milliseconds(10));
    return done;
  }
};

/// `client.call(request)` on the calling thread, its answer into `answer` (waking its waiters).
template <class Service>
void callInto(ros::ServiceClient& client, PendingCall<Service>& answer,
              typename Service::Request request) {
  Service srv;
  srv.request = std::move(request);
  const bool ok = client.call(srv);
  std::lock_guard<std::mutex> lock(answer.mutex);
  answer.done = true;
  answer.ok = ok;
  answer.response = std::move(srv.response);
  answer.answered.notify_all();
}

/// The thread of one call: `client->call(request)`, its answer into `answer`.
template <class Service>
void startCall(std::shared_ptr<ros::ServiceClient> client,
               std::shared_ptr<PendingCall<Service>> answer, typename Service::Request request) {
  std::thread([answer, client = std::move(client), request = std::move(request)]() mutable {
    callInto<Service>(*client, *answer, std::move(request));
  }).detach();
}

/// Calls `service` with `request` on its own thread, on a new non-persistent connection; wait
/// on the returned PendingCall.
template <class Service>
std::shared_ptr<PendingCall<Service>> callAsync(const ros::NodeHandle& nh,
                                                const std::string& service,
                                                typename Service::Request request) {
  ros::NodeHandle handle = nh;
  auto client = std::make_shared<ros::ServiceClient>(handle.serviceClient<Service>(service));
  auto answer = std::make_shared<PendingCall<Service>>();
  startCall<Service>(std::move(client), answer, std::move(request));
  return answer;
}

/// @brief A persistent connection to one service, opened on the first call and after drop().
/// Thread-safe; calls made while another is pending queue behind it on the same connection
/// (roscpp serializes a persistent link's calls). The connection is opened on the call's own
/// thread: a persistent ros::ServiceClient connects in its constructor, and to a host cut off
/// the network (its packets dropped) that blocks for the kernel's TCP connect timeout (about
/// 2 min): on the caller's thread the call's deadline would not hold (issue 43: a partitioned
/// worker stalled the search 2 min before it was noticed).
template <class Service>
class ServiceConnection {
 public:
  /// \param service  resolved in `nh` (relative names are remappable)
  ServiceConnection(const ros::NodeHandle& nh, const std::string& service)
      : nh_(nh), service_(service) {}

  /// Calls the service on its own thread with `request`; wait on the returned PendingCall.
  std::shared_ptr<PendingCall<Service>> callAsync(typename Service::Request request) {
    std::shared_ptr<Link> link;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!link_) link_ = std::make_shared<Link>();
      link = link_;
    }
    auto answer = std::make_shared<PendingCall<Service>>();
    std::thread([link, nh = nh_, service = service_, answer,
                 request = std::move(request)]() mutable {
      std::shared_ptr<ros::ServiceClient> client;
      {
        // Opening the link may block (see the class comment): later calls on this link wait
        // here, on their own threads, and their callers' deadlines hold.
        std::lock_guard<std::mutex> lock(link->mutex);
        if (!link->client)
          link->client = std::make_shared<ros::ServiceClient>(
              nh.serviceClient<Service>(service, /*persistent=*/true));
        client = link->client;
      }
      callInto<Service>(*client, *answer, std::move(request));
    }).detach();
    return answer;
  }

  /// Forgets the connection (its call failed or timed out): the next call opens a new one. A
  /// thread still blocked on it keeps its own reference.
  void drop() {
    std::lock_guard<std::mutex> lock(mutex_);
    link_.reset();
  }

  const std::string& service() const { return service_; }

 private:
  /// One connection: opened by the first call made on it.
  struct Link {
    std::mutex mutex;  ///< guards client
    std::shared_ptr<ros::ServiceClient> client;
  };
  ros::NodeHandle nh_;
  std::string service_;
  std::mutex mutex_;  ///< guards link_
  std::shared_ptr<Link> link_;
};

}  // namespace ros_bridge
}  // namespace reach_trajopt
