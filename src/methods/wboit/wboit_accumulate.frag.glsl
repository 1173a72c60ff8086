// Weighted blended OIT (McGuire & Bavoil 2013), accumulation pass.
// Target 0 (RGBA32F, blend ONE/ONE):            sum w*a*C, sum w*a
// Target 1 (R32F,    blend ZERO/ONE_MINUS_SRC_COLOR): revealage prod (1 - a)
// The weight functions w(z, a) are equations 7-10 of the paper; eq. 10 (window depth) is the
// default, clamped to [1e-2, 3e3] as docs/DESIGN.md, "Pipeline and formats" states.
layout(location = 0) out vec4 outAccum;
layout(location = 1) out vec4 outReveal;

uniform int u_weightFunction;  // 7, 8, 9 or 10
uniform vec2 u_projZ;          // projection[2][2], projection[3][2]: view depth from window depth

float viewDepth(float windowZ) {
    float ndc = windowZ * 2.0 - 1.0;
    return abs(u_projZ.y / (ndc + u_projZ.x));
}

float wboitWeight(float a, float windowZ) {
    if (u_weightFunction == 10) {
        float d = 1.0 - windowZ;
        return a * clamp(3e3 * d * d * d, 1e-2, 3e3);
    }
    float z = viewDepth(windowZ);
    if (u_weightFunction == 7) {
        return a * clamp(10.0 / (1e-5 + pow(z / 5.0, 2.0) + pow(z / 200.0, 6.0)), 1e-2, 3e3);
    }
    if (u_weightFunction == 8) {
        return a * clamp(10.0 / (1e-5 + pow(z / 10.0, 3.0) + pow(z / 200.0, 6.0)), 1e-2, 3e3);
    }
    return a * clamp(0.03 / (1e-5 + pow(z / 200.0, 4.0)), 1e-2, 3e3);
}

void main() {
    vec4 s = fetchSurfaceOrDiscard();
    float w = wboitWeight(s.a, gl_FragCoord.z);
    outAccum = vec4(s.rgb * s.a, s.a) * w;
    outReveal = vec4(s.a);
}
