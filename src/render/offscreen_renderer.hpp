// Renders a scene with one method for N frames (one camera, or a camera path) and gathers the
// docs/USAGE.md, "Command line" statistics, optionally per frame and against a reference method at the same
// cameras. This is what `starnt render`, `starnt bench`, the tests and the viewer's screenshots call.
#pragma once
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene_gpu.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/tools/camera_path.hpp"
#include "starnt/tools/image.hpp"

namespace starnt {

// One displayed frame of a sequence, handed to RenderJob::onFrame right after it was rendered.
struct FrameRecord {
    int index = 0;
    Camera camera;
    // "frame", "frame_ms", "interpolated", "pass_ms", "scale_pass2", "scale_pass3", "w_bar" and,
    // with a reference method, "mse" and "flip".
    nlohmann::json stats;
    const Image* image = nullptr;      // linear; set when RenderJob::readEveryFrame
    const Image* reference = nullptr;  // set when RenderJob::referenceMethod is not empty
};

struct RenderJob {
    std::string method = "abuffer";
    MethodOptions methodOptions;
    int width = 1920;
    int height = 1080;
    Camera camera;                   // used when there is no path
    std::optional<CameraPath> path;  // frame i uses path->frame(i, frames)
    glm::vec3 background{1.0f};
    float alphaCutoff = 0.03f;
    SurfaceOptions surface;
    int frames = 1;  // timings are medians over the frames after the first (shader warm-up)
    // Frames rendered first at the first camera, neither timed nor compared nor passed to onFrame
    // (shader compiles; tiles that move one level a frame). With warm-up frames every one of the
    // `frames` frames is timed. With temporal frames the warm-up runs on to the end of its group, so
    // that the first timed frame is real ("warmup_frames" in the summary counts them all).
    int warmupFrames = 0;
    // When set (e.g. "abuffer"), every frame is also rendered (untimed) with this method at the same
    // camera and compared: per-frame "mse"/"flip", and means split into real and interpolated frames.
    std::string referenceMethod;
    MethodOptions referenceOptions;  // its options
    // Instead of referenceMethod: reference images already rendered at the same cameras, frame i
    // compared with (*referenceImages)[i]. Lets `starnt bench` render the ground truth once per
    // scene rather than once per method. Needs at least `frames` images of the job's size.
    const std::vector<Image>* referenceImages = nullptr;
    // Measure the error on frames i with i % qualityEvery < 3 only (1: every frame).
    int qualityEvery = 1;
    double flipPixelsPerDegree = 67.02;
    bool readEveryFrame = false;  // read each frame back (FrameRecord::image)
    bool readTileOverlay = false;  // RenderOutput::tileOverlay of the last frame (methods with tiles)
    std::function<void(const FrameRecord&)> onFrame;
};

// A job of the given size and frame counts over `background`, the rest at its defaults: what the
// render command and the bench start from.
RenderJob sizedJob(int width, int height, int frames, int warmupFrames, const glm::vec3& background, float alphaCutoff);

struct RenderOutput {
    Image image;                         // last frame, linear
    std::optional<Image> tileOverlay;    // last frame's tile levels over the image, when asked and available
    nlohmann::json stats;                // docs/USAGE.md, "Command line" fields plus method counters
};

// Largest width or height accepted (larger is an error).
constexpr int kMaxImageSize = kMaxImageSide;  // starnt/tools/image.hpp: what the tools read and write
// Throws starnt::Error unless 1 <= width, height <= kMaxImageSize.
void checkImageSize(int width, int height);

RenderOutput renderScene(const SceneGpu& scene, const RenderJob& job);

double median(std::vector<double> values);
// Resident memory of this process in bytes (/proc/self/statm; 0 where it cannot be read). Per-frame
// records carry it as "rss_bytes" beside the method's GPU "memory_bytes", so a long run (a soak)
// shows whether either grows.
size_t residentMemoryBytes();
double mean(const std::vector<double>& values);

// The interpolated frame whose error stands out most from the real frames beside it: its MSE over
// the mean MSE of the nearest real frame before and after it (one side at the ends of a run).
// A corrected or warped frame that goes wrong shows as a flash in an otherwise steady sequence;
// a mean over all interpolated frames hides it. nullopt without an interpolated frame.
// With real frames of MSE 0 beside a frame of some error the ratio is infinite (JSON null);
// `mse` and `realBeside` say what it compares.
struct InterpolatedFlash {
    double ratio = 0.0;
    int frame = -1;
    double mse = 0.0, realBeside = 0.0;
};
std::optional<InterpolatedFlash> worstInterpolatedFlash(const std::vector<std::pair<bool, double>>& msePerFrame);

}  // namespace starnt
