// Adaptive screen-space tiles (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"), shared by the C++ reference and the GLSL passes.
// Keep it to #defines: it is included from both languages.
#ifndef STARNT_TILE_CONSTANTS_H
#define STARNT_TILE_CONSTANTS_H

// Base tile edge in pixels; quadtree leaves are 16, 8, 4 or 2 pixels (levels 0..3).
#define STARNT_TILE_SIZE 16

// Mask bits (21 of 32 used): bit 0 splits the 16x16 root; bits 1..4 split its quadrants (8x8);
// bits 5..20 split the 4x4 nodes, the children of quadrant q at bits 5 + 4q .. 8 + 4q. Quadrant
// and child order is row-major from the bottom-left (GL window coordinates): index = 2 * qy + qx.
#define STARNT_TILE_BIT_ROOT 0u
#define STARNT_TILE_BIT_QUADRANT0 1u
#define STARNT_TILE_BIT_CHILD0 5u
#define STARNT_TILE_MASK_LEVEL1 0x1u       /* bit 0 */
#define STARNT_TILE_MASK_LEVEL2 0x1Fu      /* bits 0..4 */
#define STARNT_TILE_MASK_LEVEL3 0x1FFFFFu  /* bits 0..20 */

// Split / merge thresholds on the corner variation D by node size. A node splits when
// D > split; a node that was split stays split while D >= merge (split > merge: hysteresis).
#define STARNT_TILE_SPLIT_16 0.04
#define STARNT_TILE_SPLIT_8 0.020
#define STARNT_TILE_SPLIT_4 0.0125
#define STARNT_TILE_MERGE_16 0.035
#define STARNT_TILE_MERGE_8 0.018
#define STARNT_TILE_MERGE_4 0.0115

// Jacobi iterations of the neighbour balance (k in the paper).
#define STARNT_TILE_BALANCE_ITERATIONS 2

// Scale offsets: s_p = clamp(2^(w_bar - delta_p), 0.25, 1) (the paper's formula; the default
// rule snaps it to a power of two, docs/DESIGN.md, "Adaptive tiles and tile-guided resolution").
#define STARNT_SCALE_DELTA_PASS2 2.2
#define STARNT_SCALE_DELTA_PASS3 3.0
#define STARNT_SCALE_MIN 0.25

// Scale guard (beyond the paper, docs/DESIGN.md, "Adaptive tiles and tile-guided resolution" / docs/DESIGN.md, "Scale guard"): on a probe frame (passes 2/3 at full
// resolution) the loss of rendering passes 2/3 at 1/2 or 1/4 is predicted from the full-resolution
// image: the sRGB squared error of replacing what the passes add by its bilinear reconstruction
// from every 2nd / 4th pixel (tiles::guardScales). The cheapest scales whose predicted loss adds at
// most BUDGET to the MSE over the occupied pixels (2.5e-5: an RMS shift of 0.005, 1.3/255) are used
// until the next probe. Chosen on the built-in scenes only, by the rule "a reduction may add at
// most half of starnt-full's own error on each built-in scene" (docs/DESIGN.md, "Scale guard");
// there the prediction matched the measured MSE rise within 5-35 %.
#define STARNT_SCALE_GUARD_BUDGET 2.5e-5
// Real frames between probe frames once the tiles have settled; the first
// STARNT_SCALE_SETTLE_FRAMES real frames after a reset are all probes (levels move by one a frame).
#define STARNT_SCALE_PROBE_INTERVAL 8
// Each probe in a row whose guard kept both passes at full resolution doubles the interval, up to
// STARNT_SCALE_PROBE_INTERVAL << STARNT_SCALE_PROBE_BACKOFF real frames (32); a probe that finds a
// reduction, or a reset, returns it to 8. A probe costs a full-resolution frame plus the tiles and
// the guard (22-43 ms on llvmpipe at 1280x720, 13-scene bench; docs/DESIGN.md, "Scale guard, tile signal and scale rules"): every 8th frame that made the
// default starnt 9-20 % slower than starnt-full on scenes where it never reduces.
#define STARNT_SCALE_PROBE_BACKOFF 2
#define STARNT_SCALE_SETTLE_FRAMES 3
// The guard evaluates one pixel of every 2x2 block, picked by an integer hash of the block
// (tiles::guardPixelOfBlock): an unbiased estimate of the sums over the four classes of the
// reduced sample grids, at a quarter of the cost, with one busy invocation per block (llvmpipe runs
// every lane of a branch; measured at 720p there the per-pixel evaluation took 180-250 ms per probe).
// Layout of the guard sums (floats after the four histogram counts in the readback buffer).
#define STARNT_GUARD_OCCUPIED 0
#define STARNT_GUARD_ENERGY_PASS2 1
#define STARNT_GUARD_LOSS_PASS2_HALF 2
#define STARNT_GUARD_LOSS_PASS2_QUARTER 3
#define STARNT_GUARD_ENERGY_PASS3 4
#define STARNT_GUARD_LOSS_PASS3_HALF 5
#define STARNT_GUARD_LOSS_PASS3_QUARTER 6
#define STARNT_GUARD_VALUES 7  /* indices 0..6 above */
// Below this transmittance in front of a pass's share, the share is not divided out (invisible).
#define STARNT_GUARD_MIN_TRANSMITTANCE 1e-4

// Per-tile pass-3 shading rates (docs/DESIGN.md, "Per-tile shading rates on GPUs"; GPUs with a
// shading-rate image only): on a probe frame each 16x16 tile gets the coarsest rate whose predicted
// pass-3 loss in that tile stays within STARNT_SCALE_GUARD_BUDGET x its occupied pixels
// (tiles::tileShadingRate, tile_shading_rate.comp.glsl), one texel of the shading-rate image per
// tile; the palette maps the classes to 1, 1/4 and 1/16 of the fragment-shader invocations.
// After the guard sums, the readback buffer holds the occupied tiles of each class.
#define STARNT_SHADING_RATE_FULL 0u     /* one invocation per pixel */
#define STARNT_SHADING_RATE_HALF 1u     /* one per 2x2 pixels (the guard's scale 1/2) */
#define STARNT_SHADING_RATE_QUARTER 2u  /* one per 4x4 pixels (the guard's scale 1/4) */
#define STARNT_SHADING_RATE_CLASSES 3

#endif
