#pragma once
// What every part of the service shares: the device, the configuration, the counters, the
// sessions, the frame scheduler and the worker pool. Members are destroyed in reverse order: the
// scheduler stops first, then the pool finishes its jobs, then the sessions go.
#include <atomic>
#include <chrono>
#include <memory>

#include "gpu/context.h"
#include "service/config.h"
#include "service/frame_scheduler.h"
#include "service/metrics.h"
#include "service/session_registry.h"
#include "service/stream_list.h"
#include "service/warm_up.h"
#include "service/work_pool.h"

namespace strata::service {

struct ServiceCore {
  ServiceCore(const gpu::Context& context, ServiceConfig cfg)
      : ctx(context), config(std::move(cfg)), registry(config, metrics), pool(config.encode_threads) {}

  // The compiler a new session starts progressively with (null: its first frame compiles).
  WarmUp* progressive_start() const { return config.compile.progressive_start ? compiler.get() : nullptr; }

  const gpu::Context& ctx;
  const ServiceConfig config;
  const std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  ServiceMetrics metrics;
  std::atomic<bool> draining{false};
  // Compiles pipelines ahead of their first dispatch, when config.compile asks for it (created by
  // Server before it listens); destroyed after the sessions whose jobs it holds.
  std::unique_ptr<WarmUp> compiler;
  SessionRegistry registry;
  StreamList streams;
  WorkPool pool;
  FrameScheduler scheduler;
};

}  // namespace strata::service
