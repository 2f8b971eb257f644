#pragma once
// Every live stream, attached to a session or not, for drain and for enforcing end deadlines.
#include <memory>
#include <mutex>
#include <vector>

#include "service/session.h"

namespace strata::service {

class StreamList {
 public:
  void add(const std::shared_ptr<AttachedStream>& stream) {
    std::lock_guard lock(mu_);
    streams_.push_back(stream);
  }
  // The streams still alive (forgets the others).
  std::vector<std::shared_ptr<AttachedStream>> live() {
    std::lock_guard lock(mu_);
    std::vector<std::shared_ptr<AttachedStream>> out;
    std::vector<std::weak_ptr<AttachedStream>> kept;
    for (auto& w : streams_)
      if (auto s = w.lock()) {
        out.push_back(s);
        kept.push_back(w);
      }
    streams_ = std::move(kept);
    return out;
  }

 private:
  std::mutex mu_;
  std::vector<std::weak_ptr<AttachedStream>> streams_;
};

}  // namespace strata::service
