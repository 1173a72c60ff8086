// The built-in scene renderer's opaque pass (SceneGpu::drawOpaque): materials with alphaMode OPAQUE
// and MASK, lit as the transparent surfaces are (scene_surface.frag.glsl), alpha ignored (glTF),
// MASK fragments below the material's alphaCutoff discarded. Depth test LESS with depth writes, as
// an engine draws its opaque scene before the transparent methods run.
uniform float u_maskCutoff;  // < 0: OPAQUE (no alpha test)
layout(location = 0) out vec4 outColor;

void main() {
    vec4 s = starntSurface();
    if (u_maskCutoff >= 0.0 && !(s.a >= u_maskCutoff)) discard;
    outColor = vec4(clamp(s.rgb, vec3(0.0), vec3(1.0)), 1.0);
}
