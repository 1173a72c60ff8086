// Constants of hybrid-moments' tail colour (tail_moments.glsl), shared by the shader and its CPU
// reference nn::momentWeightedTailColor (included from C++ and GLSL; keep it to #defines).
#ifndef STARNT_TAIL_MOMENTS_CONSTANTS_H
#define STARNT_TAIL_MOMENTS_CONSTANTS_H

// The depth coordinate of the moments: u = ln(1 + (z - z2) / (s (1 - z2))) for a fragment at window
// depth z behind pass 2's layer at z2, s this fraction of the window-depth range left behind z2.
// Logarithmic (as MBOIT warps its depth) so that a few fragments far behind a dense tail do not
// stretch the interval the tail's opacity is spread over (DESIGN.md, "hybrid-moments": hair seen
// from above, the head shell far behind the strands); linear below s.
#define STARNT_TAIL_MOMENT_DEPTH_SCALE 1e-3
// The quadratic weight must keep falling over the interval [0, 1] and as far again beyond its
// middle: where its minimum lies before this x the linear weight is used instead (a convex
// least-squares fit of a steep exp(-tau x) rises again at the back, weighting far fragments as if
// they were in front).
#define STARNT_TAIL_MOMENT_MIN_VERTEX 2.0
// The moments are 32-bit float sums of u and u^2;
// centring them on the tail's mean depth multiplies their rounding (about N 2^-24 relative after N
// additions) by (mean / spread)^2 for the quadratic term and mean / spread for the linear one.
// Below these spread-to-mean ratios the quadratic weight (then the linear one) is dropped: for a
// relative error under 1e-3 with N up to ~100 the bounds are about 0.08 and 6e-4. Checked on the
// built-in scenes at 320x180 (DESIGN.md, "hybrid-moments"): float sums without the guard lost up to
// 6x the double-precision accuracy (curtains), any quadratic threshold in 0.003..0.1 recovered it.
#define STARNT_TAIL_MOMENT_LINEAR_BELOW 0.03
#define STARNT_TAIL_MOMENT_PLAIN_BELOW 0.0009
// The tail's optical depth -ln t_tail is clamped here (t_tail = 1e-13): beyond, exp(-tau x) is
// zero to float precision everywhere but at the front.
#define STARNT_TAIL_MOMENT_MAX_OPTICAL_DEPTH 30.0
// Below this optical depth the integrals of x^k exp(-tau x) over [0, 1] come from their series
// (the closed forms cancel there).
#define STARNT_TAIL_MOMENT_SERIES_BELOW 1.0

#endif
