#include "http/dashboard_hub.h"

#include <algorithm>


namespace strata::http {

std::optional<std::string> DashboardHub::Viewer::next(std::chrono::milliseconds timeout) {
  std::shared_ptr<const DashboardEvent> e;
  {
    std::unique_lock lock(mu_);
    cv_.wait_for(lock, timeout, [&] { return closed_ || !queue_.empty(); });
    if (closed_ || queue_.empty()) return std::nullopt;
    e = std::move(queue_.front());
    queue_.pop_front();
  }
  return e->text();  // the PNG and the text are made here, on the viewer's thread
}

bool DashboardHub::Viewer::closed() const {
  std::lock_guard lock(mu_);
  return closed_;
}

uint64_t DashboardHub::Viewer::dropped() const {
  std::lock_guard lock(mu_);
  return dropped_;
}

std::shared_ptr<DashboardHub::Viewer> DashboardHub::subscribe() {
  std::lock_guard lock(mu_);
  if (closed_ || viewers_.size() >= k_max_viewers) return nullptr;
  viewers_.push_back(std::make_shared<Viewer>());
  return viewers_.back();
}

void DashboardHub::unsubscribe(const std::shared_ptr<Viewer>& viewer) {
  std::lock_guard lock(mu_);
  viewers_.erase(std::remove(viewers_.begin(), viewers_.end(), viewer), viewers_.end());
}

void DashboardHub::close_all() {
  std::vector<std::shared_ptr<Viewer>> all;
  {
    std::lock_guard lock(mu_);
    closed_ = true;
    all = viewers_;
  }
  for (const auto& v : all) {
    std::lock_guard lock(v->mu_);
    v->closed_ = true;
    v->cv_.notify_all();
  }
}

size_t DashboardHub::viewers() const {
  std::lock_guard lock(mu_);
  return viewers_.size();
}

void DashboardHub::publish(std::shared_ptr<const DashboardEvent> event) {
  std::vector<std::shared_ptr<Viewer>> all;
  {
    std::lock_guard lock(mu_);
    all = viewers_;
  }
  for (const auto& v : all) {
    std::lock_guard lock(v->mu_);
    if (v->queue_.size() >= k_queue_limit) {  // the viewer is behind: its oldest event goes
      v->queue_.pop_front();
      ++v->dropped_;
      dropped_.fetch_add(1);
    }
    v->queue_.push_back(event);
    v->cv_.notify_one();
  }
}

void DashboardHub::on_frame(const service::FrameEvent& event) {
  bool thumbnail = false;
  {
    std::lock_guard lock(mu_);
    if (viewers_.empty()) return;  // nobody watches: no cost per frame
    const auto now = std::chrono::steady_clock::now();
    auto [it, fresh] = last_thumbnail_.try_emplace(event.session, now);
    if (fresh || now - it->second >= k_thumbnail_period) {
      it->second = now;
      thumbnail = true;
    }
    // Forget sessions not seen for a minute, so the map stays as small as the live sessions.
    if (last_thumbnail_.size() > 256)
      std::erase_if(last_thumbnail_, [&](const auto& e) { return now - e.second > std::chrono::minutes(1); });
  }
  publish(make_frame_event(event, thumbnail));
}

}  // namespace strata::http
