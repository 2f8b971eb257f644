#pragma once
// Who else wants to know about each rendered frame (Prometheus metrics, the live dashboard). The
// session calls every observer on the scheduler thread right after rendering, so an observer must
// be quick and must not block: it copies what it needs and returns.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace strata::render {
struct FrameResult;
}

namespace strata::service {

struct RenderedFrame;

// What a session tells its observers about one frame (references valid during the call only).
struct FrameEvent {
  const std::string& session;  // sessions/{id}: for the dashboard, never a Prometheus label
  const std::string& scene;
  const std::string& method;
  const RenderedFrame& frame;
};

class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  virtual void on_frame(const FrameEvent& event) = 0;
};

// The observers of one server. Adding is rare (at start-up); notifying takes a snapshot so that an
// observer added meanwhile neither blocks nor is missed by the next frame.
class FrameObservers {
 public:
  void add(std::shared_ptr<FrameObserver> observer) {
    std::lock_guard lock(mu_);
    auto next = std::make_shared<List>();
    if (list_) *next = *list_;
    next->push_back(std::move(observer));
    list_ = std::move(next);
  }
  void notify(const FrameEvent& event) const {
    std::shared_ptr<const List> list;
    {
      std::lock_guard lock(mu_);
      list = list_;
    }
    if (!list) return;
    for (const auto& o : *list) o->on_frame(event);
  }

 private:
  using List = std::vector<std::shared_ptr<FrameObserver>>;
  mutable std::mutex mu_;
  std::shared_ptr<const List> list_;
};

}  // namespace strata::service
