// Descriptor bindings (set 0) shared by every pass and by server/render; one number per resource.
#ifndef STRATA_BINDINGS_H
#define STRATA_BINDINGS_H

#define BINDING_TLAS 0
#define BINDING_VERTICES 1
#define BINDING_INDICES 2
#define BINDING_PRIMITIVES 3
#define BINDING_INSTANCES 4
#define BINDING_MATERIALS 5
#define BINDING_EMITTERS 6
#define BINDING_ALIAS 7
#define BINDING_FRAME 8
#define BINDING_COUNTERS 9
#define BINDING_ACCUM 10
#define BINDING_PROBE_RAYS 11  // ray_probe pass: rays in
#define BINDING_PROBE_HITS 12  // ray_probe pass: hits out

// Specialization constants of the passes (constant_id).
#define SPEC_THIN_LENS 0
#define SPEC_ENV_NEE 1
#define SPEC_EMITTERS 2

#endif
