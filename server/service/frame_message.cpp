#include "service/frame_message.h"

#include <stdexcept>

#include "service/encoding.h"

namespace strata::service {

void fill_statistics(const render::FrameStats& s, v1::FrameStatistics* out) {
  for (const auto& [kind, n] : s.rays_traced) (*out->mutable_rays_traced())[kind] = n;
  out->set_rays_total(s.rays_total());
  out->set_paths(s.paths);
  out->set_nonfinite_rejected(s.nonfinite_rejected);
  for (const auto& [group, bytes] : s.memory_bytes) (*out->mutable_memory_bytes())[group] = bytes;
  for (const auto& p : s.passes) {
    auto* d = out->add_passes();
    d->set_pass(p.pass);
    d->set_ran(p.ran);
    d->set_reason(p.reason);
  }
  out->set_tlas_builds(s.tlas_builds);
  out->set_tlas_refits(s.tlas_refits);
  // Only the methods with reuse count shifts; pt leaves both empty and the message absent.
  if (!s.reuse.empty() || !s.shift_failures.empty()) {
    auto* reuse = out->mutable_reuse();
    for (const auto& [name, n] : s.reuse) (*reuse->mutable_counters())[name] = n;
    for (const auto& [reason, n] : s.shift_failures) (*reuse->mutable_shift_failures())[reason] = n;
    // The splat methods' per-pixel statistics (RS-main): splats per pixel, the fullest pixel, holes.
    if (auto landed = s.reuse.find("splat.landed"); landed != s.reuse.end() && s.pixels > 0) {
      auto* splats = reuse->mutable_splats();
      splats->set_mean_per_pixel(double(landed->second) / double(s.pixels));
      splats->set_max_per_pixel(uint32_t(s.reuse.at("splat.max_per_pixel")));
      splats->set_holes(s.reuse.at("temporal.no_history"));
    }
    // Pixel-layer domains (restir-multilayer; ML Table 1).
    if (s.reuse.contains("domains.deep")) {
      for (uint32_t layer = 0;; ++layer) {
        auto n = s.reuse.find("domains.active_layer_" + std::to_string(layer));
        if (n == s.reuse.end()) break;
        reuse->add_active_domains_by_layer(n->second);
      }
      auto get = [&](const char* key) { return s.reuse.contains(key) ? s.reuse.at(key) : uint64_t(0); };
      reuse->set_deep_domains(get("domains.deep"));
      reuse->set_uniform_deep_domains(get("domains.uniform_deep"));
      reuse->set_disoccluded_pixels(get("domains.disoccluded"));
      reuse->set_disoccluded_covered(get("domains.disoccluded_covered"));
      const uint64_t disoccluded = get("domains.disoccluded");
      reuse->set_coverage_rate(disoccluded > 0 ? double(get("domains.disoccluded_covered")) / double(disoccluded) : 0.0);
    }
  }
}

v1::Frame make_frame_message(const RenderedFrame& f) {
  v1::Frame m;
  m.set_frame_index(f.frame_index);
  m.set_input_sequence(f.input_sequence);
  double encode_ms = 0.0;
  for (auto encoding : f.encodings) {
    v1::Image* img = m.add_images();
    if (encoding == v1::IMAGE_ENCODING_DOMAIN_MAP) {
      if (!f.result.domain_map) throw std::logic_error("DOMAIN_MAP requested of a frame without a domain map");
      *img = encode_domain_map(*f.result.domain_map);
    } else {
      *img = encode_image(f.result.image, encoding, f.exposure);
    }
    encode_ms += img->encode_ms();
  }
  for (const auto& p : f.result.stats.pass_ms) {
    auto* t = m.add_pass_ms();
    t->set_pass(p.pass);
    t->set_ms(p.ms);
  }
  m.set_gpu_ms_total(f.result.stats.gpu_ms_total);
  fill_statistics(f.result.stats, m.mutable_statistics());
  m.set_frames_dropped(f.dropped_before);
  m.set_inputs_coalesced(f.coalesced);
  m.set_history_reset(f.history_reset);
  m.set_history_reset_reason(f.history_reset_reason);
  for (const auto& d : f.option_changes) *m.add_option_changes() = d;
  m.mutable_timing()->set_queued_ms(f.queued_ms);
  m.mutable_timing()->set_render_ms(f.render_ms);
  m.mutable_timing()->set_encode_ms(encode_ms);
  m.mutable_resolution()->set_width(f.result.image.width);
  m.mutable_resolution()->set_height(f.result.image.height);
  return m;
}

}  // namespace strata::service
