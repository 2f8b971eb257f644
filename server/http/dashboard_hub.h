#pragma once
// Fans rendered frames out to the dashboard's viewers (/events). Each viewer has a bounded queue:
// a viewer that reads slower than frames arrive loses its oldest events (counted), so a slow or
// stalled browser never makes the server hold more than k_queue_limit events for it. Nothing is
// built for a frame while nobody watches.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "http/frame_event_json.h"
#include "service/frame_observer.h"

namespace strata::http {

class DashboardHub final : public service::FrameObserver {
 public:
  static constexpr size_t k_queue_limit = 64;   // events held for one viewer
  static constexpr size_t k_max_viewers = 8;    // /events connections at once
  static constexpr auto k_thumbnail_period = std::chrono::milliseconds(500);  // per session

  class Viewer {
   public:
    // The next event's text, waiting at most `timeout`; nullopt on timeout or once closed.
    std::optional<std::string> next(std::chrono::milliseconds timeout);
    bool closed() const;
    uint64_t dropped() const;

   private:
    friend class DashboardHub;
    mutable std::mutex mu_;
    std::condition_variable cv_;
    std::deque<std::shared_ptr<const DashboardEvent>> queue_;
    uint64_t dropped_ = 0;
    bool closed_ = false;
  };

  // nullptr when k_max_viewers are connected already.
  std::shared_ptr<Viewer> subscribe();
  void unsubscribe(const std::shared_ptr<Viewer>& viewer);
  // Wakes and closes every viewer (server shutdown).
  void close_all();

  void on_frame(const service::FrameEvent& event) override;
  // Publishes one event to every viewer (shared: its text is made once, off the frame path).
  void publish(std::shared_ptr<const DashboardEvent> event);
  void publish(const std::string& text) { publish(std::make_shared<const DashboardEvent>(text)); }

  size_t viewers() const;
  uint64_t events_dropped() const { return dropped_.load(); }

 private:
  mutable std::mutex mu_;
  std::vector<std::shared_ptr<Viewer>> viewers_;
  std::map<std::string, std::chrono::steady_clock::time_point> last_thumbnail_;  // by session
  std::atomic<uint64_t> dropped_{0};
  bool closed_ = false;
};

}  // namespace strata::http
