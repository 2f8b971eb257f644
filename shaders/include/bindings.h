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
#define BINDING_TLAS_PREV 13       // the previous frame's TLAS (methods with temporal reuse)
#define BINDING_INSTANCES_PREV 14  // the previous frame's instance records
#define BINDING_RESTIR 15          // GpuRestirConstants (uniform)
#define BINDING_RESERVOIRS_IN 16   // reservoirs a pass reads at other pixels (history, neighbours)
#define BINDING_RESERVOIRS_OUT 17  // reservoirs a pass writes (and reads at its own pixel)
#define BINDING_CONTRIBUTION 18    // per pixel: f(Y) of the reservoir at that pixel, in its domain
#define BINDING_DISOCCLUSION 19    // disocclusion pass: one uint per pixel out
// Reservoir splatting's counting sort (RS-supp 3.1), restir-splat:
#define BINDING_SPLATS 20          // per time partition and previous pixel: its reservoir splatted into this frame (SplatRecord)
#define BINDING_SPLAT_TARGET 21    // per time partition and previous pixel: the current pixel it landed in (SPLAT_NONE: failed)
#define BINDING_SPLAT_COUNT 22     // per current pixel: splats that landed there (atomic counters)
#define BINDING_SPLAT_OFFSETS 23   // per current pixel + 1: exclusive prefix sum of the counts
#define BINDING_SPLAT_LIST 24      // the splat records, grouped by the current pixel they landed in
#define BINDING_PRIMARY 25         // the visibility buffer (GpuPrimaryHit per pixel) of this frame
#define BINDING_PRIMARY_PREV 26    // ... and of the previous frame
// The spatial stage's pixels without history, run apart in a dense list (restir_spatial.comp):
#define BINDING_SPATIAL_LIST 27    // pixel indices
#define BINDING_SPATIAL_ARGS 28    // VkDispatchIndirectCommand (workgroups) and the list's length
#define BINDING_SPATIAL_PAIRS 29   // per pixel and pair slot: the paired neighbour's sample shifted into it (PairShift)
#define BINDING_SWEPT_BOXES 30     // the changed instances' swept boxes (GpuSweptBoxes; with the previous frame)
// Pixel-layer domains (restir-multilayer; restir/layer_data.h, stage domain_init):
#define BINDING_DOMAINS 31         // per domain of this frame: depth range, flags, occluder (GpuDomainRange)
#define BINDING_DOMAINS_PREV 32    // ... and of the previous frame
#define BINDING_DOMAIN_MARKS 33    // per domain: the occluders of the representative hits propagated into it (uvec2)
#define BINDING_DOMAIN_LIST 34     // the active deep domains, compacted (domain indices)
#define BINDING_DOMAIN_ARGS 35     // VkDispatchIndirectCommand (workgroups) and the list's length
#define BINDING_DOMAIN_LIST_PREV 38  // ... the previous frame's list (its active deep domains propagate and splat)
#define BINDING_DOMAIN_ARGS_PREV 39  // ... and its length
// LoD-aware reuse (with history; restir/lod_mapping.h, render/lod_uv_space.h)
#define BINDING_LOD_UV 36          // the UV-space TLAS: every LoD level's triangles at their UVs, a plane per instance
#define BINDING_LOD_TABLE 37       // GpuLodHeader, then a GpuLodInstance per instance
// Textures and alpha-tested materials (passes' textured variants, compiled with STRATA_TEXTURES;
// include/texture_data.h, include/textures.glsl): bound only for scenes that have them.
#define BINDING_MATERIAL_TEXTURES 40  // per material: GpuMaterialTextures
#define BINDING_TEXTURES 41           // per texture: GpuTexture
#define BINDING_TEXTURE_LEVELS 42     // GpuMipLevel of every image's chain
#define BINDING_TEXELS 43             // linear RGBA16 texels of every level
#define BINDING_VERTEX_EXTRAS 44      // per vertex: GpuVertexExtra (tangent, TEXCOORD_1), or one unused record
#define BINDING_LIGHT_EMISSION 45     // per triangle (index array / 3): the emission NEE selects it by (scenes with emissive textures)
#define BINDING_TEMPORAL_FROM_Q 46     // per pixel: p-hat from q of the canonical sample (restir_temporal_reverse -> restir_temporal)
#define BINDING_PRIMARY_MATERIAL 47       // textured scenes, fixed primary vertices: the material of each visibility-buffer entry (GpuPrimaryMaterial)
#define BINDING_PRIMARY_MATERIAL_PREV 48  // ... and of the previous frame's entries
// The deformation pass (deform.comp; scenes with skins or morph targets, include/deform_data.h):
#define BINDING_DEFORM_JOBS 49        // GpuDeformJob per deforming primitive of the slot being written
#define BINDING_DEFORM_VERTEX_JOB 50  // per deformed vertex of a slot: its job (index into the slot's jobs)
#define BINDING_MORPH_DELTAS 51       // GpuMorphDelta of every morph target's vertices
#define BINDING_SKIN_VERTICES 52      // GpuSkinVertex of every skinned vertex
#define BINDING_SKIN_MATRICES 53      // GpuSkinMatrix of the frame, per skinned instance and joint
#define BINDING_MORPH_WEIGHTS 54      // the frame's morph weights, per morphing instance and target

// Specialization constants of the passes (constant_id).
#define SPEC_THIN_LENS 0
#define SPEC_ENV_NEE 1
#define SPEC_EMITTERS 2
#define SPEC_MOTION_BLUR 3
#define SPEC_SPATIAL_COMPACT 5  // restir_spatial.comp: pixels that draw neighbours at random go to that list
#define SPEC_SPATIAL_PAIRS 6    // restir_spatial.comp: the first two neighbours are the frame's pair (restir/spatial_pairs.glsl)
#define SPEC_DOMAIN_LIST 7      // this dispatch runs a list of active deep domains (initial, splat_resample: this frame's; domain_propagate, splat_project: the previous frame's)
#define SPEC_LAYER_STEPPING 8   // restir-multilayer, layer_mode uniform / no-depth-ranges: layers by rank (restir/layers.glsl)
#define SPEC_LOD_MAPPING 9      // passes with history, scenes with LoD groups and lod_mapping on: the resolver maps across LoD switches
#define SPEC_DORMANT_LIST 10    // domain_propagate: the list dispatch runs the previous frame's dormant deep domains (restir/domain_list_prev.glsl)
#define SPEC_ALPHA_TEST 11      // textured variants, scenes with alpha-tested materials: rays are not forced opaque
#define SPEC_PUNCTUAL 12        // passes that sample lights, scenes with punctual lights: the light table's punctual entries (include/scene_lights.glsl)
#define SPEC_ENV_MAP 13         // scenes with an environment map: escaped rays and environment NEE read it (include/scene_lights.glsl)
#define SPEC_LIGHT_TREE 14      // light_sampler tree: lights are chosen by the frame's light tree (include/scene_lights.glsl)

#endif
