#include "ops/service_collector.h"

#include <map>
#include <string>

#include <grpcpp/grpcpp.h>

namespace strata::ops {
namespace {

using prometheus::ClientMetric;
using prometheus::MetricFamily;
using prometheus::MetricType;

MetricFamily one(const char* name, const char* help, MetricType type, double value) {
  ClientMetric m;
  if (type == MetricType::Counter) m.counter.value = value;
  else m.gauge.value = value;
  return {name, help, type, {m}};
}

}  // namespace

std::vector<MetricFamily> ServiceCollector::Collect() const {
  const auto& m = core_.metrics;
  const auto sessions = core_.registry.list();
  std::map<std::string, double> memory;
  for (const auto& s : sessions) {
    const v1::Session d = s->describe(core_.config);  // named: a temporary would die before the loop runs
    for (const auto& [group, bytes] : d.memory().bytes_by_group()) memory[group] += double(bytes);
  }

  std::vector<MetricFamily> out;
  out.push_back(one("strata_sessions_active", "Open sessions", MetricType::Gauge, double(sessions.size())));
  out.push_back(one("strata_streams_active", "Open Stream calls", MetricType::Gauge, double(m.streams.load())));
  out.push_back(one("strata_sessions_created_total", "Sessions created", MetricType::Counter, double(m.sessions_created.load())));
  out.push_back(one("strata_sessions_expired_total", "Sessions removed after idle_timeout without a stream", MetricType::Counter,
                    double(m.sessions_expired.load())));
  out.push_back(one("strata_frames_dropped_total", "Rendered frames replaced by a newer one before their client took them",
                    MetricType::Counter, double(m.frames_dropped.load())));
  out.push_back(one("strata_inputs_coalesced_total", "Frame inputs merged into a later one before rendering", MetricType::Counter,
                    double(m.inputs_coalesced.load())));
  out.push_back(one("strata_buffered_frame_bytes", "Bytes of rendered frames the streams hold (in slots, encoding or writing)",
                    MetricType::Gauge, double(std::max<int64_t>(0, m.buffered_frame_bytes.load()))));
  out.push_back(one("strata_max_sessions", "The max_sessions limit", MetricType::Gauge, double(core_.config.limits.max_sessions)));
  out.push_back(one("strata_draining", "1 while the server drains (SIGTERM)", MetricType::Gauge, core_.draining.load() ? 1.0 : 0.0));
  out.push_back(one("strata_uptime_seconds", "Seconds since the service started", MetricType::Gauge,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - core_.started).count()));

  MetricFamily mem{"strata_device_memory_bytes", "Device memory of every session, by buffer group", MetricType::Gauge, {}};
  for (const auto& [group, bytes] : memory) {
    ClientMetric c;
    c.label = {{"group", group}};
    c.gauge.value = bytes;
    mem.metric.push_back(std::move(c));
  }
  out.push_back(std::move(mem));

  // The _info convention: a gauge of 1 whose labels carry the build's metadata.
  ClientMetric info;
  info.label = {{"device", core_.ctx.device_name()}, {"grpc_version", grpc::Version()}, {"version", STRATA_VERSION}};
  info.gauge.value = 1.0;
  out.push_back({"strata_build_info", "strata's version, the gRPC library version and the Vulkan device", MetricType::Gauge, {info}});
  return out;
}

}  // namespace strata::ops
