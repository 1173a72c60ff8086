// Built-in scene renderer, vertex stage. Positions are world space (node transforms are baked at
// load time), so only the camera transforms them.
#include "scene/scene_constants.h"

layout(location = STARNT_ATTRIB_POSITION) in vec3 a_position;
layout(location = STARNT_ATTRIB_NORMAL) in vec3 a_normal;
layout(location = STARNT_ATTRIB_UV) in vec2 a_uv;
layout(location = STARNT_ATTRIB_COLOR) in vec4 a_color;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_viewPosition;
out vec3 v_viewNormal;
out vec2 v_uv;
out vec4 v_color;

// Depth peeling compares a fragment's depth across passes bit for bit.
invariant gl_Position;

void main() {
    vec4 viewPosition = u_view * vec4(a_position, 1.0);
    v_viewPosition = viewPosition.xyz;
    v_viewNormal = mat3(u_view) * a_normal;
    v_uv = a_uv;
    v_color = a_color;
    gl_Position = u_projection * viewPosition;
}
