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

float mboitFractionInFront(float b0, vec2 moments[MBOIT_COUNT], float z) {
    const int n = MBOIT_ORDER;
    vec2 b[n + 1];
    b[0] = vec2(1.0, 0.0);
    for (int k = 1; k <= n; ++k) b[k] = moments[k - 1] * ((1.0 - u_momentBias) / b0);
    // LDL^H of the Hermitian Toeplitz matrix M_jk = b_{j-k}.
    vec2 L[(n + 1) * (n + 1)];
    // Every entry read is written first (column k before row j > k reads it); zeroed so that the
    // compiler can see that too (Mesa warns, and debug contexts turn the warning into an error).
    for (int i = 0; i < (n + 1) * (n + 1); ++i) L[i] = vec2(0.0);
    float D[n + 1];
    for (int j = 0; j <= n; ++j) {
        float dj = 1.0;
        for (int k = 0; k < j; ++k) dj -= dot(L[j * (n + 1) + k], L[j * (n + 1) + k]) * D[k];
        D[j] = dj;
        for (int i = j + 1; i <= n; ++i) {
            vec2 lij = b[i - j];
            for (int k = 0; k < j; ++k) lij -= cmul(L[i * (n + 1) + k], cconj(L[j * (n + 1) + k])) * D[k];
            L[i * (n + 1) + j] = lij / dj;
        }
    }
    float phase = mboitPhase(z);
    vec2 x0 = vec2(cos(phase), sin(phase));
    vec2 q[n + 1];
    for (int i = 0; i <= n; ++i) q[i] = vec2(0.0);  // written before read; zeroed for the compiler
    vec2 xk = vec2(1.0, 0.0);
    for (int j = 0; j <= n; ++j) {
        vec2 y = xk;
        for (int k = 0; k < j; ++k) y -= cmul(L[j * (n + 1) + k], q[k]);
        q[j] = y;
        xk = cmul(xk, x0);
    }
    for (int j = 0; j <= n; ++j) q[j] /= D[j];
    for (int j = n; j >= 0; --j) {
        for (int k = j + 1; k <= n; ++k) q[j] -= cmul(cconj(L[k * (n + 1) + j]), q[k]);
    }
    vec2 kernel[n + 1];
    for (int k = 0; k <= n; ++k) kernel[k] = cconj(q[k]);
    vec2 roots[n];
    mboitRoots(kernel, roots);
    // Support points and the indicator of "in front of x0".
    vec2 x[n + 1];
    float f[n + 1];
    x[0] = x0;
    f[0] = u_overestimation;
    float zoneStart = 2.0 * MBOIT_PI - u_wrapAngle;
    for (int i = 1; i <= n; ++i) {
        vec2 r = roots[i - 1];
        float len = length(r);
        x[i] = len > 0.0 ? r / len : vec2(1.0, 0.0);
        float angle = atan(x[i].y, x[i].x);
        if (angle < 0.0) angle += 2.0 * MBOIT_PI;
        f[i] = angle > zoneStart ? (angle - zoneStart) / u_wrapAngle : (angle < phase ? 1.0 : 0.0);
    }
    // Newton divided differences, then the monomial coefficients of the interpolating polynomial.
    vec2 d[n + 1];
    for (int i = 0; i <= n; ++i) d[i] = vec2(f[i], 0.0);
    for (int j = 1; j <= n; ++j) {
        for (int i = n; i >= j; --i) d[i] = cdiv(d[i] - d[i - 1], x[i] - x[i - j]);
    }
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

float mboitFractionInFront(float b0, float moments[MBOIT_COUNT], float z) {
    const int n = MBOIT_ORDER;
    float b[2 * n + 1];
    b[0] = 1.0;
    for (int k = 1; k <= 2 * n; ++k) b[k] = mix(moments[k - 1] / b0, u_biasVector[k - 1], u_momentBias);
    // LDL^T of the Hankel matrix M_jk = b_{j+k}.
    float L[(n + 1) * (n + 1)];
    for (int i = 0; i < (n + 1) * (n + 1); ++i) L[i] = 0.0;  // as above: written before read
    float D[n + 1];
    for (int j = 0; j <= n; ++j) {
        float dj = b[2 * j];
        for (int k = 0; k < j; ++k) dj -= L[j * (n + 1) + k] * L[j * (n + 1) + k] * D[k];
        D[j] = dj;
        for (int i = j + 1; i <= n; ++i) {
            float lij = b[i + j];
            for (int k = 0; k < j; ++k) lij -= L[i * (n + 1) + k] * L[j * (n + 1) + k] * D[k];
            L[i * (n + 1) + j] = lij / dj;
        }
    }
    float q[n + 1];
    for (int i = 0; i <= n; ++i) q[i] = 0.0;  // written before read; zeroed for the compiler
    float zk = 1.0;
    for (int j = 0; j <= n; ++j) {
        float y = zk;
        for (int k = 0; k < j; ++k) y -= L[j * (n + 1) + k] * q[k];
        q[j] = y;
        zk *= z;
    }
    for (int j = 0; j <= n; ++j) q[j] /= D[j];
    for (int j = n; j >= 0; --j) {
        for (int k = j + 1; k <= n; ++k) q[j] -= L[k * (n + 1) + j] * q[k];
    }
    float roots[n];
    mboitRoots(q, roots);

    float x[n + 1];
    float f[n + 1];
    x[0] = z;
    f[0] = u_overestimation;
    for (int i = 1; i <= n; ++i) {
        x[i] = roots[i - 1];
        f[i] = x[i] < z ? 1.0 : 0.0;
    }
    float d[n + 1];
    for (int i = 0; i <= n; ++i) d[i] = f[i];
    for (int j = 1; j <= n; ++j) {
        for (int i = n; i >= j; --i) d[i] = (d[i] - d[i - 1]) / (x[i] - x[i - j]);
    }
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
