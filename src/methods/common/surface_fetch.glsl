// Wraps the engine's starntSurface(): applies the alpha cut-off every pass shares (docs/DESIGN.md, "Pipeline and formats":
// fragments with alpha below it are discarded in all passes) and clamps to valid ranges.
uniform float u_alphaCutoff;

vec4 fetchSurfaceOrDiscard() {
    vec4 s = starntSurface();
    s = clamp(s, vec4(0.0), vec4(1.0));
    if (!(s.a >= u_alphaCutoff)) discard;  // also discards NaN alpha
    return s;
}
