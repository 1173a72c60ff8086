// One triangle covering the viewport; no vertex attributes. It lies on the far plane (clip z = w,
// window depth 1 under the default depth range): passes that test it against pass-1 depth shade
// only where pass 1 drew (methods/neural/empty_pixels.hpp); every other full-screen pass runs with
// the depth test off, where its depth does not matter.
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
}
