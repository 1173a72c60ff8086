// The matrices a reprojection runs on (see reprojection_cpu.hpp for the algorithm). Runtime
// (reprojector.cpp) and the CPU reference share them.
#pragma once
#include <glm/glm.hpp>

namespace starnt::temporal {

// What the search needs from the two cameras, computed in double and rounded once.
struct Reprojection {
    glm::vec4 row0{1, 0, 0, 0}, row1{0, 1, 0, 0}, row3{0, 0, 0, 1};  // rows 0, 1, 3 of R
    glm::vec4 sourceScale{0, 0, 0, 1};  // row 3 of inverse(oldViewProj): . v = 1 / old view depth
};
Reprojection makeReprojection(const glm::mat4& oldViewProj, const glm::mat4& newViewProj);

// Corrected frames (correction_cpu.hpp): the matrices of the composite,
// oldViewProj * inverse(newViewProj) and row 3 of inverse(oldViewProj), in double, rounded once.
struct CorrectionMatrices {
    glm::mat4 newToOld{1.0f};
    glm::vec4 sourceScale{0, 0, 0, 1};
};
CorrectionMatrices makeCorrectionMatrices(const glm::mat4& oldViewProj, const glm::mat4& newViewProj);

}  // namespace starnt::temporal
