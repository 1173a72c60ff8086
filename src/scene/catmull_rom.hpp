// Uniform Catmull-Rom interpolation, shared by camera paths (camera_path.cpp) and the built-in
// scenes' strands (builtin_scenes.cpp).
#pragma once
#include <glm/glm.hpp>

namespace starnt {

// The curve through p1 (u = 0) and p2 (u = 1), with neighbours p0 and p3; u in [0, 1].
inline glm::vec3 catmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3, float u) {
    const float u2 = u * u, u3 = u2 * u;
    return 0.5f * ((2.0f * p1) + (-p0 + p2) * u + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * u2 +
                   (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * u3);
}

}  // namespace starnt
