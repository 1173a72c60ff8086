// The saturated RGB hue ramp, shared by the built-in scenes (float, their colours are part of the
// shipped weights' training data, so the arithmetic must not change) and the procedural training
// families (double).
#pragma once
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace starnt {

// The fully saturated colour of hue `hue01` in [0, 1) (red, yellow, green, cyan, blue, magenta),
// mixed with white by `pastel`.
template <class T>
glm::vec<3, T> hueColor(T hue01, T pastel) {
    const T h = hue01 * T(6);
    const T x = T(1) - std::fabs(std::fmod(h, T(2)) - T(1));
    glm::vec<3, T> c;
    switch (std::min(int(h), 5)) {
        case 0: c = {1, x, 0}; break;
        case 1: c = {x, 1, 0}; break;
        case 2: c = {0, 1, x}; break;
        case 3: c = {0, x, 1}; break;
        case 4: c = {x, 0, 1}; break;
        default: c = {1, 0, x}; break;
    }
    return glm::mix(c, glm::vec<3, T>(T(1)), pastel);
}

}  // namespace starnt
