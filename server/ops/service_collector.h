#pragma once
// The service's state as Prometheus metrics, read when scraped (nothing to keep in step): sessions
// active and streams open, the ServiceMetrics counters (sessions created and expired, frames
// dropped, inputs coalesced), device memory by buffer group over every session, the bytes of
// frames the streams hold, uptime, and strata_build_info.
#include <vector>

#include <prometheus/collectable.h>
#include <prometheus/metric_family.h>

#include "service/service_core.h"

namespace strata::ops {

class ServiceCollector final : public prometheus::Collectable {
 public:
  explicit ServiceCollector(service::ServiceCore& core) : core_(core) {}
  std::vector<prometheus::MetricFamily> Collect() const override;

 private:
  service::ServiceCore& core_;
};

}  // namespace strata::ops
