/* The GL binding points the STAR-NT methods use: what an engine must know to share a context with
 * them. Included from C++ and from the methods' GLSL (keep it to #defines).
 *
 * During OitMethod::render the methods bind their own textures, images and storage buffers to the
 * points below and leave them bound afterwards (INTEGRATION.md, in the source tree's docs/, lists the state a method
 * changes). An engine's surface shader (SurfaceShader), which runs inside the methods' geometry
 * passes, must therefore take its own textures from units at or above
 * STARNT_ENGINE_FIRST_TEXTURE_UNIT, its images from image units at or above
 * STARNT_ENGINE_FIRST_IMAGE_UNIT and its storage buffers from bindings at or above
 * STARNT_ENGINE_FIRST_SSBO_BINDING; uniform buffer bindings are all the engine's. */
#ifndef STARNT_BINDINGS_H
#define STARNT_BINDINGS_H

/* ---- What is left to the engine ---- */
#define STARNT_ENGINE_FIRST_TEXTURE_UNIT 9
#define STARNT_ENGINE_FIRST_IMAGE_UNIT 2
#define STARNT_ENGINE_FIRST_SSBO_BINDING 9

/* ---- Texture units the neural methods read their pass outputs from (composite, inference) ---- */
#define STARNT_UNIT_NEAREST 0        /* pass 1: C1, a1 (full resolution) */
#define STARNT_UNIT_SECOND 1         /* pass 2: C2, a2 */
#define STARNT_UNIT_ALPHA_COLOR 2    /* pass 3: sum a C, sum a */
#define STARNT_UNIT_COLOR_COUNT 3    /* pass 3: sum C, N */
#define STARNT_UNIT_TRANSMITTANCE 4  /* pass 3: prod (1 - a) */
#define STARNT_UNIT_NEAREST_DEPTH 5  /* pass-1 window depth (joint upsampling, pass-2 peel) */
#define STARNT_UNIT_CORNER_NETWORK 6 /* corner inference: the network at leaf corners */
#define STARNT_UNIT_LAYER_ALPHA 7    /* dfaoit's narrow layers: a1, a2 (full resolution) */
/* hybrid-moments' tail depth moments (full resolution). They share units 6 and 7 with the corner
 * network and the narrow layers' alphas, which hybrid-moments never uses (NeuralMethod rejects
 * corner inference for it; narrow layers are DFAOIT's). */
#define STARNT_UNIT_TAIL_MOMENT1 6
#define STARNT_UNIT_TAIL_MOMENT2 7
/* Every method: the engine's opaque scene (FrameDesc::backgroundTexture in the composites,
 * FrameDesc::opaqueDepth where the methods copy it into their own depth targets). Bound through a
 * sampler object of the method's (nearest, clamped, no depth compare), so the engine's filter and
 * compare parameters never matter and are never changed; its base level, depth-stencil mode and
 * swizzle are the defaults during render() and the engine's again when it returns. */
#define STARNT_UNIT_OPAQUE 8

/* ---- Shader storage buffer bindings ---- */
#define STARNT_SSBO_ABUFFER_HEADS 0
#define STARNT_SSBO_ABUFFER_NODES 1
#define STARNT_SSBO_ABUFFER_COUNTERS 2
#define STARNT_SSBO_ABUFFER_ORDERS 3
/* Adaptive tiles: masks read (previous / current), masks written, per-tile occupancy, histogram. */
#define STARNT_SSBO_TILE_MASKS_IN 4
#define STARNT_SSBO_TILE_MASKS_OUT 5
#define STARNT_SSBO_TILE_OCCUPANCY 6
#define STARNT_SSBO_TILE_HISTOGRAM 7
/* Scale guard: per-tile sums. */
#define STARNT_SSBO_TILE_GUARD 8

/* Largest linear colour channel a surface may return (HDR); larger values are clamped to it. With
 * 16-bit float sums (65504 at most) it leaves room for 100 layers of alpha 0.6. */
#define STARNT_MAX_SURFACE_COLOR 1024.0

/* A-buffer list terminator. */
#define STARNT_ABUFFER_END 0xFFFFFFFFu

#endif
