// Adaptive screen-space tiles (SPEC section 4), shared by the C++ reference and the GLSL passes.
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

// Scale offsets: s_p = clamp(2^(w_bar - delta_p), 0.25, 1).
#define STARNT_SCALE_DELTA_PASS2 2.2
#define STARNT_SCALE_DELTA_PASS3 3.0
#define STARNT_SCALE_MIN 0.25

#endif
