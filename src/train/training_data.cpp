#include "train/training_data.hpp"

#include "reference/fragment_capture.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/error.hpp"

namespace starnt {

std::vector<FragmentList> captureTrainingLists(const CaptureSetOptions& o) {
    std::vector<FragmentList> lists;
    FragmentCapture capture(SceneGpu::surfaceShader());
    const size_t total = o.scenes.size() * o.seeds.size() * o.azimuths.size() * o.elevations.size() *
                         o.alphaOverrides.size();
    size_t done = 0;
    for (const std::string& name : o.scenes) {
        for (uint32_t seed : o.seeds) {
            Scene scene = makeBuiltinScene(name, seed);
            SceneGpu gpu(scene);
            const float aspect = float(o.width) / float(o.height);
            for (float az : o.azimuths) {
                for (float el : o.elevations) {
                    Camera cam = orbitCamera(scene.bounds(), az, el, aspect);
                    FrameDesc frame;
                    frame.width = o.width;
                    frame.height = o.height;
                    frame.view = cam.view();
                    frame.projection = cam.projection(aspect);
                    for (float alpha : o.alphaOverrides) {
                        SurfaceOptions surface;
                        if (alpha >= 0.0f) surface.alphaOverride = alpha;
                        gpu.drawOpaque(frame, surface);  // the fragments the methods see: clipped by it
                        CapturedFrame captured =
                            capture.capture(frame, gpu.callback(frame.view, frame.projection, surface));
                        for (auto& list : captured.pixels) {
                            if (!list.empty()) lists.push_back(std::move(list));
                        }
                        if (o.progress) o.progress(++done, total);
                    }
                }
            }
        }
    }
    return lists;
}

}  // namespace starnt
