// The previous frame's compacted list of active deep domains (ML Sec. 5: "we compact all active
// domains into a contiguous buffer and assign one thread per domain"): domain_fill.comp wrote it as
// that frame's list; this frame's domain_propagate and splat_project run it (SPEC_DOMAIN_LIST, an
// indirect dispatch with DOMAIN_LIST_GROUP threads per workgroup) instead of every previous deep
// domain, most of which are inactive and hold nothing. With SPEC_DORMANT_LIST the dispatch runs the
// list's other end instead, the previous frame's dormant deep domains (domain_propagate only: they
// hold no sample). Needs restir/layer_data.h and the bindings.
#ifndef STRATA_DOMAIN_LIST_PREV_GLSL
#define STRATA_DOMAIN_LIST_PREV_GLSL

layout(set = 0, binding = BINDING_DOMAIN_LIST_PREV, std430) readonly buffer DomainListPrev { uint b_domain_list_prev[]; };
layout(set = 0, binding = BINDING_DOMAIN_ARGS_PREV, std430) readonly buffer DomainArgsPrev { GpuDomainArgs b_domain_args_prev[2]; };
layout(constant_id = SPEC_DOMAIN_LIST) const bool k_domain_list = false;
layout(constant_id = SPEC_DORMANT_LIST) const bool k_dormant_list = false;

// This invocation's previous domain in a list dispatch; false past the list's end.
bool prev_list_entry(out uint domain) {
  uint i = gl_WorkGroupID.x * DOMAIN_LIST_GROUP + gl_LocalInvocationIndex;
  uint count = b_domain_args_prev[k_dormant_list ? DOMAIN_ARGS_DORMANT : DOMAIN_ARGS_ACTIVE].count;
  domain = 0u;
  if (i >= count) return false;
  domain = b_domain_list_prev[k_dormant_list ? dormant_list_slot(i, restir_layers(), image_size(true).x, image_size(true).y) : i];
  return true;
}

#endif
