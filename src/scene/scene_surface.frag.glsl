// Built-in scene renderer, surface function (docs/DESIGN.md, "Shading").
// Base = baseColorFactor x baseColorTexture x COLOR_0 (linear; the texture is sRGB-decoded by its
// GL format). Alpha = base alpha, or u_alphaOverride when >= 0. Unlit materials return the base
// unchanged. Lit materials: a headlight Lambert term plus ambient,
//   rgb = base.rgb * (0.35 + 0.65 * |n . v|) + emissive,
// two-sided (|n . v|) because every suite material is double-sided and seen from both sides.
// Meshes without normals use the face normal from screen-space derivatives.
#include "scene/scene_constants.h"

in vec3 v_viewPosition;
in vec3 v_viewNormal;
in vec2 v_uv;
in vec4 v_color;

uniform vec4 u_baseColorFactor;
uniform int u_hasTexture;
uniform int u_unlit;
uniform int u_hasNormals;
uniform float u_alphaOverride;
uniform vec3 u_emissive;  // glTF emissiveFactor (x KHR_materials_emissive_strength), added after the lighting
layout(binding = STARNT_SURFACE_TEXTURE_UNIT) uniform sampler2D u_baseColorTexture;

const float kAmbient = 0.35;

vec4 starntSurface() {
    vec4 base = u_baseColorFactor * v_color;
    if (u_hasTexture != 0) base *= texture(u_baseColorTexture, v_uv);
    if (u_alphaOverride >= 0.0) base.a = u_alphaOverride;
    if (u_unlit != 0) return vec4(base.rgb + u_emissive, base.a);
    vec3 faceNormal = cross(dFdx(v_viewPosition), dFdy(v_viewPosition));
    vec3 n = (u_hasNormals != 0 && dot(v_viewNormal, v_viewNormal) > 1e-20) ? v_viewNormal : faceNormal;
    float len = length(n);
    float lambert = len > 0.0 ? abs(dot(n / len, normalize(-v_viewPosition))) : 1.0;
    return vec4(base.rgb * (kAmbient + (1.0 - kAmbient) * lambert) + u_emissive, base.a);
}
