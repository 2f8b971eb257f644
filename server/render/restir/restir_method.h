#pragma once
// Every ReSTIR method: the stages of its method-table row (method_table.h) over one RestirState,
// recorded top to bottom in one place (record()). Stages an option switches off are not built.
#include <memory>
#include <vector>

#include "render/method.h"
#include "render/method_table.h"
#include "render/restir/restir_state.h"
#include "render/restir/stage.h"

namespace strata::render {

class RestirMethod : public Method {
 public:
  RestirMethod(const SharedResources& shared, const RenderSettings& settings, const MethodSpec& spec);
  ~RestirMethod() override;
  uint32_t timed_passes() const override;
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) override;
  std::vector<PassDecision> decisions() const override;
  std::map<std::string, uint64_t> memory_bytes() const override;
  void collect(std::span<const uint32_t> counters, FrameStats& stats) const override;
  bool fixed_primary() const override { return state_.spec.fixed_primary; }
  std::optional<DomainMap> domain_map() const override;

 private:
  const Stage* find(StageKind kind) const;
  RestirState state_;
  int last_parity_ = 0;  // the parity of the last recorded frame (its domain ranges are current there)
  std::vector<std::unique_ptr<Stage>> stages_;  // in frame order
};

}  // namespace strata::render
