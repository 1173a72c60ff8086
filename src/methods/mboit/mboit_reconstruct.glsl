// MBOIT: transmittance at a depth reconstructed from the moments of optical depth (the paper's
// bounds: Hamburger problem for 4 and 6 power moments, the trigonometric moment problem for 2 and 3
// complex moments). Same formulas as the CPU reference mboit_cpu.cpp:
//  1. normalise by b_0 and bias: power b <- (1 - beta) b + beta * biasVector, trig b <- (1 - beta) b;
//  2. M = Hankel (M_jk = b_{j+k}) or Toeplitz (M_jk = b_{j-k}) matrix, size n + 1; solve
//     M q = v(x0), v(x) = (1, x, .., x^n), x0 = z (power) or exp(i phi(z)) (trig), by LDL^T / LDL^H;
//  3. the n roots of sum_k conj(q_k) x^k are the other support points x_1..x_n of the canonical
//     representation through x0 (quadratic / cubic formulas; trig roots projected onto the circle);
//  4. with f_0 = eta (overestimation 0.25) and f_i = 1 for the points in front of x0 (0 behind, a
//     linear ramp across the trigonometric wrapping zone), the optical depth in front of x0 as a
//     fraction of b_0 is sum_k p_k b_k for the degree-n polynomial p with p(x_i) = f_i. eta = 0 gives
//     the lower bound, eta = 1 the upper bound, eta = 0.25 their 3:1 mix (the paper's setting);
//  5. T = exp(-b_0 * clamp(fraction, 0, 1)).
#include "methods/mboit/mboit_common.glsl"

uniform float u_momentBias;
uniform float u_biasVector[6];
uniform float u_overestimation;

#if MBOIT_TRIG
vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 cconj(vec2 a) { return vec2(a.x, -a.y); }
vec2 cdiv(vec2 a, vec2 b) { return cmul(a, cconj(b)) / dot(b, b); }
// Both moment kinds run one algorithm (mboitFractionInFront below) over their own scalar: complex
// numbers as vec2 for trigonometric moments, float for power moments.
#define MBOIT_SCALAR vec2
#define MBOIT_B_COUNT (MBOIT_ORDER + 1)
#define MBOIT_ONE vec2(1.0, 0.0)
#define mboitMul(a, b) cmul(a, b)
#define mboitDiv(a, b) cdiv(a, b)
#define mboitConj(a) cconj(a)
#define mboitReal(a) (a).x
#define mboitFromReal(a) vec2(a, 0.0)
#define mboitNorm2(a) dot(a, a)
#else
#define MBOIT_SCALAR float
#define MBOIT_B_COUNT (2 * MBOIT_ORDER + 1)
#define MBOIT_ONE 1.0
#define mboitMul(a, b) ((a) * (b))
#define mboitDiv(a, b) ((a) / (b))
#define mboitConj(a) (a)
#define mboitReal(a) (a)
#define mboitFromReal(a) (a)
#define mboitNorm2(a) ((a) * (a))
#endif

// Step 2's solve once M = L D L^H is factored (L unit lower triangular, row-major (n + 1)^2), for
// both moment kinds: forward substitution, the diagonal, back substitution.
void mboitSolve(MBOIT_SCALAR L[(MBOIT_ORDER + 1) * (MBOIT_ORDER + 1)], float D[MBOIT_ORDER + 1], MBOIT_SCALAR x0,
                out MBOIT_SCALAR q[MBOIT_ORDER + 1]) {
    const int n = MBOIT_ORDER;
    for (int i = 0; i <= n; ++i) q[i] = MBOIT_SCALAR(0.0);  // written before read; zeroed for the compiler
    MBOIT_SCALAR xk = MBOIT_ONE;
    for (int j = 0; j <= n; ++j) {
        MBOIT_SCALAR y = xk;
        for (int k = 0; k < j; ++k) y -= mboitMul(L[j * (n + 1) + k], q[k]);
        q[j] = y;
        xk = mboitMul(xk, x0);
    }
    for (int j = 0; j <= n; ++j) q[j] /= D[j];
    for (int j = n; j >= 0; --j) {
        for (int k = j + 1; k <= n; ++k) q[j] -= mboitMul(mboitConj(L[k * (n + 1) + j]), q[k]);
    }
}

#if MBOIT_TRIG
vec2 csqrt(vec2 z) {
    float r = length(z);
    float re = sqrt(max(0.5 * (r + z.x), 0.0));
    float im = sqrt(max(0.5 * (r - z.x), 0.0));
    return vec2(re, z.y < 0.0 ? -im : im);
}
vec2 ccbrt(vec2 z) {
    float r = length(z);
    if (r == 0.0) return vec2(0.0);
    float angle = atan(z.y, z.x) / 3.0;
    return pow(r, 1.0 / 3.0) * vec2(cos(angle), sin(angle));
}

// Roots of c[0] + c[1] x + .. + c[n] x^n, complex coefficients.
void mboitRoots(vec2 c[MBOIT_ORDER + 1], out vec2 roots[MBOIT_ORDER]) {
#if MBOIT_ORDER == 2
    // x^2 + B x + C; the root of larger magnitude first, the other from Vieta (no cancellation).
    vec2 B = cdiv(c[1], c[2]), C = cdiv(c[0], c[2]);
    vec2 d = csqrt(cmul(B, B) - 4.0 * C);
    if (dot(B, d) < 0.0) d = -d;
    vec2 big = -0.5 * (B + d);
    roots[0] = big;
    roots[1] = dot(big, big) > 0.0 ? cdiv(C, big) : vec2(0.0);
#else
    // Cardano on the monic cubic x^3 + a x^2 + b x + c, depressed by x = t - a / 3.
    vec2 a = cdiv(c[2], c[3]), b = cdiv(c[1], c[3]), cc = cdiv(c[0], c[3]);
    vec2 a2 = cmul(a, a);
    vec2 p = b - a2 / 3.0;
    vec2 q = cmul(a2, a) * (2.0 / 27.0) - cmul(a, b) / 3.0 + cc;
    vec2 s = csqrt(cmul(q, q) * 0.25 + cmul(cmul(p, p), p) / 27.0);
    vec2 u3 = -0.5 * q + s;
    vec2 other = -0.5 * q - s;
    if (dot(other, other) > dot(u3, u3)) u3 = other;
    vec2 u = ccbrt(u3);
    const vec2 omega = vec2(-0.5, 0.86602540378);
    for (int k = 0; k < 3; ++k) {
        vec2 t = dot(u, u) > 0.0 ? u - cdiv(p, 3.0 * u) : vec2(0.0);
        roots[k] = t - a / 3.0;
        u = cmul(u, omega);
    }
#endif
}

// Step 1: b_0 = 1, then b_k for k = 1..n.
void mboitNormalise(float b0, vec2 moments[MBOIT_COUNT], out vec2 b[MBOIT_B_COUNT]) {
    b[0] = vec2(1.0, 0.0);
    for (int k = 1; k <= MBOIT_ORDER; ++k) b[k] = moments[k - 1] * ((1.0 - u_momentBias) / b0);
}
// M_ij (i >= j) of the Hermitian Toeplitz matrix.
#define MBOIT_MATRIX(b, i, j) b[(i) - (j)]
// Where the depth z lies in the moments' domain (its phase), computed once per reconstruction.
float mboitPosition(float z) { return mboitPhase(z); }
// x0 on the unit circle at that phase.
vec2 mboitPoint(float phase) { return vec2(cos(phase), sin(phase)); }
// Support point x_i from a kernel root (projected onto the circle) and its indicator f_i: 1 in front
// of the phase, 0 behind, a linear ramp across the wrapping zone.
float mboitSupport(vec2 root, float phase, out vec2 x) {
    float len = length(root);
    x = len > 0.0 ? root / len : vec2(1.0, 0.0);
    float angle = atan(x.y, x.x);
    if (angle < 0.0) angle += 2.0 * MBOIT_PI;
    float zoneStart = 2.0 * MBOIT_PI - u_wrapAngle;
    return angle > zoneStart ? (angle - zoneStart) / u_wrapAngle : (angle < phase ? 1.0 : 0.0);
}
// sum_k p_k b_k (real part) for the polynomial p in Newton form (divided differences d, points x).
float mboitPolynomialSum(vec2 d[MBOIT_ORDER + 1], vec2 x[MBOIT_ORDER + 1], vec2 b[MBOIT_B_COUNT]) {
    const int n = MBOIT_ORDER;
    // Monomial coefficients (lowest first, real and imaginary parts) of the Newton form:
    // p <- p * (x - x_i) + d_i. (Whole-vector updates, as in the power case below: an in-place loop
    // over a coefficient array gave wrong results on Mesa llvmpipe.)
    vec4 re = vec4(d[n].x, 0.0, 0.0, 0.0), im = vec4(d[n].y, 0.0, 0.0, 0.0);
    for (int i = n - 1; i >= 0; --i) {
        vec4 newRe = vec4(d[i].x, re.xyz) - (x[i].x * re - x[i].y * im);
        vec4 newIm = vec4(d[i].y, im.xyz) - (x[i].x * im + x[i].y * re);
        re = newRe;
        im = newIm;
    }
    float sum = 0.0;
    for (int k = 0; k <= n; ++k) sum += re[k] * b[k].x - im[k] * b[k].y;
    return sum;
}

#else  // power moments

// Real roots of c[0] + c[1] x + .. + c[n] x^n (all real for a positive definite Hankel matrix).
void mboitRoots(float c[MBOIT_ORDER + 1], out float roots[MBOIT_ORDER]) {
#if MBOIT_ORDER == 2
    float disc = sqrt(max(c[1] * c[1] - 4.0 * c[2] * c[0], 0.0));
    float big = -0.5 * (c[1] + (c[1] < 0.0 ? -disc : disc));
    roots[0] = big / c[2];
    roots[1] = c[0] / big;
#else
    // Trigonometric solution of the depressed cubic t^3 + p t + q (three real roots: p < 0).
    float a = c[2] / c[3], b = c[1] / c[3], cc = c[0] / c[3];
    float p = b - a * a / 3.0;
    float q = 2.0 * a * a * a / 27.0 - a * b / 3.0 + cc;
    float r = 2.0 * sqrt(max(-p / 3.0, 0.0));
    float cos3 = r > 0.0 ? clamp(3.0 * q / (p * r), -1.0, 1.0) : 0.0;
    float theta = acos(cos3) / 3.0;
    for (int k = 0; k < 3; ++k) roots[k] = r * cos(theta - 2.0 * MBOIT_PI * float(k) / 3.0) - a / 3.0;
#endif
}

// Step 1: b_0 = 1, then b_k for k = 1..2n.
void mboitNormalise(float b0, float moments[MBOIT_COUNT], out float b[MBOIT_B_COUNT]) {
    b[0] = 1.0;
    for (int k = 1; k <= 2 * MBOIT_ORDER; ++k) b[k] = mix(moments[k - 1] / b0, u_biasVector[k - 1], u_momentBias);
}
// M_ij of the Hankel matrix.
#define MBOIT_MATRIX(b, i, j) b[(i) + (j)]
float mboitPosition(float z) { return z; }
float mboitPoint(float z) { return z; }
// Support point x_i (a kernel root) and its indicator f_i: 1 in front of z, 0 behind.
float mboitSupport(float root, float z, out float x) {
    x = root;
    return x < z ? 1.0 : 0.0;
}
// sum_k p_k b_k for the polynomial p in Newton form (divided differences d, points x).
float mboitPolynomialSum(float d[MBOIT_ORDER + 1], float x[MBOIT_ORDER + 1], float b[MBOIT_B_COUNT]) {
    const int n = MBOIT_ORDER;
    // Monomial coefficients (lowest first) of the Newton form: p <- p * (x - x_i) + d_i. (A whole-
    // vector update: the in-place loop over a float array, p[k] = p[k-1] - p[k] * x_i for k = n..1,
    // gave wrong coefficients on Mesa llvmpipe (LLVM 15) while its C++ transcription is right.)
    vec4 p = vec4(d[n], 0.0, 0.0, 0.0);
    for (int i = n - 1; i >= 0; --i) p = vec4(d[i], p.xyz) - x[i] * p;
    float sum = p.x;
    for (int k = 1; k <= n; ++k) sum += p[k] * b[k];
    return sum;
}
#endif

// Steps 2-4 for both kinds, with the kind's hooks above (mboitNormalise, MBOIT_MATRIX, mboitPosition,
// mboitPoint, mboitSupport, mboitPolynomialSum).
float mboitFractionInFront(float b0, MBOIT_SCALAR moments[MBOIT_COUNT], float z) {
    const int n = MBOIT_ORDER;
    MBOIT_SCALAR b[MBOIT_B_COUNT];
    mboitNormalise(b0, moments, b);
    // L D L^H = M.
    MBOIT_SCALAR L[(n + 1) * (n + 1)];
    // Every entry read is written first (column k before row j > k reads it); zeroed so that the
    // compiler can see that too (Mesa warns, and debug contexts turn the warning into an error).
    for (int i = 0; i < (n + 1) * (n + 1); ++i) L[i] = MBOIT_SCALAR(0.0);
    float D[n + 1];
    for (int j = 0; j <= n; ++j) {
        float dj = mboitReal(MBOIT_MATRIX(b, j, j));
        for (int k = 0; k < j; ++k) dj -= mboitNorm2(L[j * (n + 1) + k]) * D[k];
        D[j] = dj;
        for (int i = j + 1; i <= n; ++i) {
            MBOIT_SCALAR lij = MBOIT_MATRIX(b, i, j);
            for (int k = 0; k < j; ++k) lij -= mboitMul(L[i * (n + 1) + k], mboitConj(L[j * (n + 1) + k])) * D[k];
            L[i * (n + 1) + j] = lij / dj;
        }
    }
    float position = mboitPosition(z);
    MBOIT_SCALAR x0 = mboitPoint(position);
    MBOIT_SCALAR q[n + 1];
    mboitSolve(L, D, x0, q);
    // The kernel polynomial sum_k conj(q_k) x^k, its roots, the support points.
    for (int k = 0; k <= n; ++k) q[k] = mboitConj(q[k]);
    MBOIT_SCALAR roots[n];
    mboitRoots(q, roots);
    MBOIT_SCALAR x[n + 1];
    float f[n + 1];
    x[0] = x0;
    f[0] = u_overestimation;
    for (int i = 1; i <= n; ++i) f[i] = mboitSupport(roots[i - 1], position, x[i]);
    // Newton divided differences of the interpolating polynomial.
    MBOIT_SCALAR d[n + 1];
    for (int i = 0; i <= n; ++i) d[i] = mboitFromReal(f[i]);
    for (int j = 1; j <= n; ++j) {
        for (int i = n; i >= j; --i) d[i] = mboitDiv(d[i] - d[i - 1], x[i] - x[i - j]);
    }
    return mboitPolynomialSum(d, x, b);
}

// Transmittance in front of the fragment at window depth `windowZ` of this pixel.
layout(binding = 0) uniform sampler2D u_b0;
layout(binding = 1) uniform sampler2D u_moments;
#if MBOIT_EXTRA
layout(binding = 2) uniform sampler2D u_extra;
#endif

float mboitTransmittance(ivec2 pixel, float windowZ) {
    float b0 = texelFetch(u_b0, pixel, 0).r;
    if (!(b0 > 0.0)) return 1.0;
    vec4 m = texelFetch(u_moments, pixel, 0);
#if MBOIT_EXTRA
    vec4 e = texelFetch(u_extra, pixel, 0);
#endif
    float z = mboitWarpedDepth(windowZ);
#if MBOIT_TRIG
    vec2 moments[MBOIT_COUNT];
    moments[0] = m.xy;
    moments[1] = m.zw;
#if MBOIT_EXTRA
    moments[2] = e.xy;
#endif
#else
    float moments[MBOIT_COUNT];
    moments[0] = m.x;
    moments[1] = m.y;
    moments[2] = m.z;
    moments[3] = m.w;
#if MBOIT_EXTRA
    moments[4] = e.x;
    moments[5] = e.y;
#endif
#endif
    float fraction = mboitFractionInFront(b0, moments, z);
    if (!(fraction >= 0.0)) fraction = 0.0;  // also NaN from a degenerate solve: count nothing in front
    return exp(-b0 * min(fraction, 1.0));
}
