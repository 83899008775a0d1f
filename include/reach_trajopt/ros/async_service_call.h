#pragma once
/// \file async_service_call.h
/// A ROS service call with a deadline. ros::ServiceClient::call has no timeout: a hung node
/// (stopped, deadlocked, not dead) blocks its caller for ever. callAsync() makes the call on a
/// thread of its own (detached, it owns its state: it stays blocked until that node dies) and
/// the caller waits with a deadline instead (PendingCall::waitUntil).

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

/// Calls `service` with `request` on its own thread; wait on the returned PendingCall.
template <class Service>
std::shared_ptr<PendingCall<Service>> callAsync(const ros::NodeHandle& nh,
                                                const std::string& service,
                                                typename Service::Request request) {
  auto answer = std::make_shared<PendingCall<Service>>();
  std::thread([answer, nh, service, request = std::move(request)]() mutable {
    Service srv;
    srv.request = std::move(request);
    ros::NodeHandle handle = nh;
    ros::ServiceClient client = handle.serviceClient<Service>(service);
    const bool ok = client.call(srv);
    std::lock_guard<std::mutex> lock(answer->mutex);
    answer->done = true;
    answer->ok = ok;
    answer->response = std::move(srv.response);
    answer->answered.notify_all();
  }).detach();
  return answer;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
