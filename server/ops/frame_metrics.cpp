#include "ops/frame_metrics.h"

#include "service/frame_message.h"
#include "service/session.h"

namespace strata::ops {
namespace {

// Frame latency on the server: from the input's arrival to the frame rendered (queued + render).
prometheus::Histogram::BucketBoundaries latency_buckets() {
  return {0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30};
}
// One pass's GPU time: lavapipe takes milliseconds to seconds, a real GPU tens of microseconds.
prometheus::Histogram::BucketBoundaries gpu_buckets() {
  return {0.00005, 0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 10};
}

}  // namespace

FrameMetrics::FrameMetrics(prometheus::Registry& r)
    : frames_(prometheus::BuildCounter().Name("strata_frames_rendered_total").Help("Frames rendered, by method").Register(r)),
      latency_(prometheus::BuildHistogram()
                   .Name("strata_frame_latency_seconds")
                   .Help("Server-side frame latency: from the frame's input arriving to the frame rendered (queue wait + render)")
                   .Register(r)),
      render_(prometheus::BuildHistogram()
                  .Name("strata_frame_render_seconds")
                  .Help("Wall time of rendering one frame on the server, readback included, by method")
                  .Register(r)),
      pass_gpu_(prometheus::BuildHistogram()
                    .Name("strata_frame_pass_gpu_seconds")
                    .Help("GPU time of one pass of one frame (Vulkan timestamps), by pass")
                    .Register(r)),
      frame_gpu_(prometheus::BuildHistogram()
                     .Name("strata_frame_gpu_seconds")
                     .Help("GPU time of one frame, every pass together, by method")
                     .Register(r)),
      resets_(prometheus::BuildCounter()
                  .Name("strata_history_resets_total")
                  .Help("Frames rendered without temporal history, by reason (first_frame, gpu_state_released, settings_changed)")
                  .Register(r)),
      shift_failures_(prometheus::BuildCounter()
                          .Name("strata_shift_failures_total")
                          .Help("ReSTIR shifts that failed, by pass and reason")
                          .Register(r)),
      rays_(prometheus::BuildCounter().Name("strata_rays_traced_total").Help("Rays traced, by method").Register(r)),
      domains_(prometheus::BuildCounter()
                   .Name("strata_domains_active_total")
                   .Help("Active reuse domains summed over frames, by pixel layer")
                   .Register(r)),
      disoccluded_(prometheus::BuildCounter()
                       .Name("strata_disoccluded_pixels_total")
                       .Help("Front-layer hits not visible in the previous frame, summed over frames")
                       .Register(r)
                       .Add({})),
      disoccluded_covered_(prometheus::BuildCounter()
                               .Name("strata_disoccluded_covered_pixels_total")
                               .Help("Disoccluded pixels that received a temporal sample from a deep domain, summed over frames")
                               .Register(r)
                               .Add({})) {}

std::string FrameMetrics::reset_reason_label(const std::string& reason) {
  // Session::render words its reasons; the first of them decides the label (a frame can carry
  // several, joined by "; ").
  if (reason.rfind("first frame", 0) == 0) return "first_frame";
  if (reason.find("released") != std::string::npos && reason.find("changed") == std::string::npos) return "gpu_state_released";
  return "settings_changed";
}

void FrameMetrics::on_frame(const service::FrameEvent& e) {
  const auto& f = e.frame;
  const auto& stats = f.result.stats;
  frames_.Add({{"method", e.method}}).Increment();
  latency_.Add({{"method", e.method}}, latency_buckets()).Observe((f.queued_ms + f.render_ms) / 1000.0);
  render_.Add({{"method", e.method}}, latency_buckets()).Observe(f.render_ms / 1000.0);
  frame_gpu_.Add({{"method", e.method}}, gpu_buckets()).Observe(stats.gpu_ms_total / 1000.0);
  for (const auto& p : stats.pass_ms) pass_gpu_.Add({{"pass", p.pass}}, gpu_buckets()).Observe(p.ms / 1000.0);
  if (f.history_reset) resets_.Add({{"reason", reset_reason_label(f.history_reset_reason)}}).Increment();
  rays_.Add({{"method", e.method}}).Increment(double(stats.rays_total()));

  // The wire form of the statistics is the one place where every method's counters are named;
  // reading it here picks up new statistics (multi-layer domains) as the renderer fills them.
  v1::FrameStatistics wire;
  // Only methods with reuse fill the reuse statistics; the copy costs nothing for the others.
  if (!stats.reuse.empty() || !stats.shift_failures.empty()) service::fill_statistics(stats, &wire);
  const auto& reuse = wire.reuse();
  for (const auto& [key, n] : reuse.shift_failures()) {
    const auto dot = key.find('.');
    const std::string pass = dot == std::string::npos ? "unknown" : key.substr(0, dot);
    const std::string reason = dot == std::string::npos ? key : key.substr(dot + 1);
    shift_failures_.Add({{"pass", pass}, {"reason", reason}}).Increment(double(n));
  }
  for (int layer = 0; layer < reuse.active_domains_by_layer_size(); ++layer)
    domains_.Add({{"layer", std::to_string(layer)}}).Increment(double(reuse.active_domains_by_layer(layer)));
  disoccluded_.Increment(double(reuse.disoccluded_pixels()));
  disoccluded_covered_.Increment(double(reuse.disoccluded_covered()));
}

}  // namespace strata::ops
