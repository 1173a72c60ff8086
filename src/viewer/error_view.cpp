#include "viewer/error_view.hpp"
#include "io/texture_readback.hpp"

#include <sstream>

#include "starnt/tools/metrics.hpp"
#include "viewer/display_pass.hpp"
#include "viewer/method_set.hpp"

namespace starnt::viewer {

std::string ErrorView::keyOf(int sceneGeneration, const Camera& camera, glm::ivec2 size,
                             const ViewerSettings& settings) const {
    // Everything the comparison depends on, spelled out; equal text = same inputs.
    std::ostringstream key;
    const glm::mat4 view = camera.view();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) key << view[c][r] << ',';
    key << camera.fovYDeg << ',' << camera.nearPlane << ',' << camera.farPlane << '|' << size.x << 'x' << size.y << '|'
        << sceneGeneration << '|' << settings.method << '|' << settings.alpha.value_or(-1.0f) << '|'
        << settings.background.r << ',' << settings.background.g << ',' << settings.background.b << '|'
        << int(settings.options.neural.inference) << ',' << settings.options.neural.fixedScale2 << ',' << settings.options.neural.fixedScale3
        << ',' << (settings.options.neural.spatial ? int(*settings.options.neural.spatial) : 2) << ','
        << settings.options.neural.temporalInterval << ',' << settings.options.neural.temporalAuto << ',' << settings.options.neural.targetFps;
    return key.str();
}

void ErrorView::compute(const SceneGpu& scene, int sceneGeneration, const Camera& camera, glm::ivec2 size,
                        const ViewerSettings& settings, GLuint methodOutput) {
    if (!reference_) reference_ = createMethod("abuffer", SceneGpu::surfaceShader());
    FrameDesc frame = frameDesc(camera, size, settings);
    scene.drawOpaque(frame, surfaceOptions(settings));
    reference_->render(frame, scene.callback(frame.view, frame.projection, surfaceOptions(settings)));
    const Image reference = gl::readTexture(reference_->outputTexture(), size.x, size.y);
    const Image test = gl::readTexture(methodOutput, size.x, size.y);
    const FlipResult result = flip(reference, test);
    meanFlip_ = result.mean;
    mse_ = mseSrgb(reference, test);
    heatmap_ = uploadImage(flipHeatmap(result.errorMap));
    key_ = keyOf(sceneGeneration, camera, size, settings);
}

GLuint ErrorView::heatmapFor(int sceneGeneration, const Camera& camera, glm::ivec2 size,
                             const ViewerSettings& settings) const {
    if (!heatmap_ || key_ != keyOf(sceneGeneration, camera, size, settings)) return 0;
    return heatmap_.id();
}

}  // namespace starnt::viewer
