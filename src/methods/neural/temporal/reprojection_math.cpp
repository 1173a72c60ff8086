#include "methods/neural/temporal/reprojection_math.hpp"

namespace starnt::temporal {

Reprojection makeReprojection(const glm::mat4& oldViewProj, const glm::mat4& newViewProj) {
    const glm::dmat4 inverseOld = glm::inverse(glm::dmat4(oldViewProj));
    const glm::mat4 m(glm::dmat4(newViewProj) * inverseOld);
    auto row = [](const glm::mat4& a, int r) { return glm::vec4(a[0][r], a[1][r], a[2][r], a[3][r]); };  // [column][row]
    Reprojection out;
    out.row0 = row(m, 0);
    out.row1 = row(m, 1);
    out.row3 = row(m, 3);
    out.sourceScale = row(glm::mat4(inverseOld), 3);
    return out;
}

CorrectionMatrices makeCorrectionMatrices(const glm::mat4& oldViewProj, const glm::mat4& newViewProj) {
    CorrectionMatrices m;
    m.newToOld = glm::mat4(glm::dmat4(oldViewProj) * glm::inverse(glm::dmat4(newViewProj)));
    m.sourceScale = makeReprojection(oldViewProj, newViewProj).sourceScale;
    return m;
}

}  // namespace starnt::temporal
