#pragma once
// Every ReSTIR method: the stages its method-table row (method_table.h) and options call for, over
// one RestirState, recorded top to bottom by record(): the whole frame in one function.
#include <memory>
#include <vector>

#include "render/method.h"
#include "render/method_table.h"
#include "render/restir/restir_state.h"
#include "render/restir/splat_sort.h"
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
  // work -> history.current for the domains that no spatial pass wrote (docs/ARCHITECTURE.md, "The frame").
  void record_commit(const StageFrame& f) const;

  RestirState state_;
  int last_parity_ = 0;  // the parity of the last recorded frame (its domain ranges are current there)
  // The stages, each built only when the method and options call for it (null otherwise).
  std::unique_ptr<Stage> primary_, domain_init_;
  std::unique_ptr<SplatSortStage> splat_sort_;
  std::unique_ptr<Stage> initial_, temporal_, spatial_, shade_;
  std::vector<const Stage*> built_;  // the built stages in frame order (timers, memory, statistics)
};

}  // namespace strata::render
