// Temporal reprojection (SPEC section 6) on a real GL context: the search pass against its CPU
// reference and against analytic expectations, and the TemporalFrames facade.
//
// Pixel grids are in GL order (row 0 at the bottom), as the reprojector sees its textures.
#include <cstring>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "reference/reprojection_cpu.hpp"
#include "methods/neural/temporal/reprojection_math.hpp"
#include "starnt/tools/camera.hpp"
#include "methods/neural/temporal/reprojector.hpp"
#include "methods/neural/temporal/temporal_frames.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/metrics.hpp"
#include "test_support.hpp"

using namespace starnt;
using temporal::ReprojectionFrame;

namespace {

constexpr float kFovDeg = 60.0f, kNear = 0.1f, kFar = 10.0f;

glm::mat4 projection(int w, int h) { return glm::perspective(glm::radians(kFovDeg), float(w) / float(h), kNear, kFar); }

// A camera at `eye` looking along `yawDeg` (about +Y, 0 = -Z) and `pitchDeg`.
glm::mat4 viewProj(int w, int h, glm::vec3 eye, float yawDeg, float pitchDeg = 0.0f) {
    const float yaw = glm::radians(yawDeg), pitch = glm::radians(pitchDeg);
    const glm::vec3 dir(-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
    return projection(w, h) * glm::lookAt(eye, eye + dir, glm::vec3(0, 1, 0));
}

gl::Texture2D uploadColor(const ReprojectionFrame& f) {
    gl::Texture2D t(GL_RGBA32F, f.width, f.height);
    starnt::gl::uploadTexture(t.id(), f.width, f.height, GL_RGBA, GL_FLOAT, f.color.data());
    return t;
}

gl::Texture2D uploadDepth(const ReprojectionFrame& f) {
    gl::Texture2D t(GL_DEPTH_COMPONENT32F, f.width, f.height);
    starnt::gl::uploadTexture(t.id(), f.width, f.height, GL_DEPTH_COMPONENT, GL_FLOAT, f.depth.data());
    return t;
}

std::vector<glm::vec4> download(GLuint texture, int w, int h) {
    std::vector<glm::vec4> out(size_t(w) * size_t(h));
    const std::vector<float> floats = starnt::gl::readTextureFloats(texture, w, h, 4);
    std::memcpy(out.data(), floats.data(), floats.size() * sizeof(float));
    return out;
}

std::vector<glm::vec4> reprojectOnGpu(const ReprojectionFrame& f, const glm::mat4& oldVP, const glm::mat4& newVP) {
    test::glContext();
    static temporal::Reprojector reprojector;  // programs built once per process
    gl::Texture2D color = uploadColor(f), depth = uploadDepth(f), out(GL_RGBA32F, f.width, f.height);
    reprojector.capture(color.id(), depth.id(), f.width, f.height, oldVP);
    reprojector.reproject(newVP, out.id());
    return download(out.id(), f.width, f.height);
}

ReprojectionFrame randomFrame(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    ReprojectionFrame f{w, h, {}, {}};
    for (int i = 0; i < w * h; ++i) {
        f.color.emplace_back(unit(rng), unit(rng), unit(rng), 1.0f);
        f.depth.push_back(i % 5 == 0 ? 1.0f : unit(rng));  // some "nothing drawn" pixels
    }
    return f;
}

// Pixels (GL order) where two grids differ in any channel by more than `tolerance`.
size_t countDifferent(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b, float tolerance = 0.0f) {
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const glm::vec4 d = glm::abs(a[i] - b[i]);
        if (!(std::max(std::max(d.x, d.y), std::max(d.z, d.w)) <= tolerance)) ++n;
    }
    return n;
}

// Where the ray through new pixel centre (x, y) meets the old surface of window depth `depth`, in
// old window coordinates, computed in double through world space (not the shader's closed form).
struct Analytic {
    bool valid = false;  // in front of both cameras
    glm::dvec2 window{0.0};
    double newViewDepth = 0.0;
};

Analytic analyticSource(int x, int y, double depth, int w, int h, const glm::mat4& oldVP, const glm::mat4& newVP) {
    // Two points on the new ray, carried into old NDC; the old depth plane cuts the line between.
    const glm::dmat4 toOld = glm::dmat4(oldVP) * glm::inverse(glm::dmat4(newVP));
    const glm::dvec2 c((x + 0.5) / w * 2.0 - 1.0, (y + 0.5) / h * 2.0 - 1.0);
    const glm::dvec4 a = toOld * glm::dvec4(c, -0.5, 1.0), b = toOld * glm::dvec4(c, 0.5, 1.0);
    // Old NDC z of a + t (b - a) equals zn: solve the homogeneous equation in t.
    const double zn = depth * 2.0 - 1.0;
    const double t = (zn * a.w - a.z) / ((b.z - a.z) - zn * (b.w - a.w));
    const glm::dvec4 p = a + t * (b - a);
    Analytic out;
    const glm::dvec4 world = glm::inverse(glm::dmat4(oldVP)) * p;
    const glm::dvec4 clip = glm::dmat4(newVP) * (world / world.w);
    out.valid = p.w > 0.0 && clip.w > 0.0;
    out.window = (glm::dvec2(p) / p.w * 0.5 + 0.5) * glm::dvec2(w, h);
    out.newViewDepth = clip.w;
    return out;
}

// Colours that name their pixel: (x, y, 0.5, 1), exact in float, so an output pixel tells which
// source it took.
std::vector<glm::vec4> positionColors(int w, int h) {
    std::vector<glm::vec4> c;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) c.emplace_back(float(x), float(y), 0.5f, 1.0f);
    return c;
}

// The source texel a positionColors() output pixel shows, or -1 for a colour that is no texel.
int sourceIndex(const glm::vec4& c, int w, int h) {
    const int sx = int(c.x), sy = int(c.y);
    const bool exact = c.z == 0.5f && float(sx) == c.x && float(sy) == c.y && sx >= 0 && sy >= 0 && sx < w && sy < h;
    return exact ? sy * w + sx : -1;
}

// True when output pixel (x, y) may CONSISTENTLY show source texel s: the ray through the pixel
// centre meets the old surface at s's depth inside texel s (within `eps` pixels, for float).
bool consistent(const ReprojectionFrame& f, int x, int y, int s, const glm::mat4& oldVP, const glm::mat4& newVP,
                double eps = 1e-3) {
    const Analytic a = analyticSource(x, y, f.depth[size_t(s)], f.width, f.height, oldVP, newVP);
    const int sx = s % f.width, sy = s / f.width;
    return a.valid && a.window.x > sx - eps && a.window.x < sx + 1 + eps && a.window.y > sy - eps && a.window.y < sy + 1 + eps;
}

}  // namespace

TEST(TemporalReprojection, IdenticalCameraReturnsTheInput) {
    // 1x1, odd sizes that are not multiples of the seed blocks, and a regular one.
    for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{37, 23}, std::pair{64, 48}}) {
        const ReprojectionFrame f = randomFrame(w, h, 11);
        const glm::mat4 vp = viewProj(w, h, {0.3f, -0.2f, 1.0f}, 25.0f, -10.0f);
        const std::vector<glm::vec4> gpu = reprojectOnGpu(f, vp, vp);
        EXPECT_EQ(countDifferent(gpu, f.color), 0u) << w << "x" << h;
        EXPECT_EQ(countDifferent(temporal::reprojectOnCpu(f, temporal::makeReprojection(vp, vp)), f.color), 0u);
    }
}

// Everything on the far plane and a camera that only turns: every pixel whose ray meets the old
// image shows exactly the texel it meets (the homography of the rotation, computed in double);
// the rest (content entering at the left border) keep their own old colour.
TEST(TemporalReprojection, PureRotationOfTheFarPlaneFollowsTheHomography) {
    const int w = 90, h = 60;
    const ReprojectionFrame f{w, h, positionColors(w, h), std::vector<float>(size_t(w * h), 1.0f)};
    const glm::vec3 eye(0.5f, 0.2f, -0.3f);
    const glm::mat4 oldVP = viewProj(w, h, eye, 0.0f), newVP = viewProj(w, h, eye, 6.0f, 2.0f);
    const std::vector<glm::vec4> gpu = reprojectOnGpu(f, oldVP, newVP);
    size_t followed = 0, fallbacks = 0, failures = 0;
    const double eps = 1e-3;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const Analytic a = analyticSource(x, y, 1.0, w, h, oldVP, newVP);
            ASSERT_TRUE(a.valid);
            const glm::dvec2 q = a.window;
            const int got = sourceIndex(gpu[size_t(y * w + x)], w, h);
            // Rays meeting a texel edge within eps may go either way in float: not checked.
            const glm::dvec2 frac = q - glm::floor(q);
            if (std::min({frac.x, frac.y, 1.0 - frac.x, 1.0 - frac.y}) < eps) continue;
            int want = y * w + x;  // off the old image: the pixel keeps its old colour
            if (q.x >= 0 && q.y >= 0 && q.x < w && q.y < h) {
                want = int(q.y) * w + int(q.x);
                ++followed;
            } else {
                ++fallbacks;
            }
            if (got != want && ++failures <= 8) ADD_FAILURE() << "pixel " << x << "," << y << " took " << got << ", not " << want;
        }
    }
    EXPECT_EQ(failures, 0u);
    // Turning left by 6 degrees (~5.4 px) brings in new content at the left border.
    EXPECT_GT(fallbacks, size_t(4 * h));
    EXPECT_GT(followed, size_t(w * h) * 8 / 10);
    // The CPU reference agrees (a ray meeting a texel edge may land on either side in float).
    EXPECT_LE(countDifferent(gpu, temporal::reprojectOnCpu(f, temporal::makeReprojection(oldVP, newVP))),
              size_t(w * h) / 200);
}

// Random depths (a point cloud), a camera that moves and turns: the search meets inconsistent
// depths everywhere. Every pixel still shows a texel of the old frame; many show one consistent
// with their ray (checked in double, not with the shader's closed form); GPU equals CPU.
TEST(TemporalReprojection, SourcesAreConsistentUnderMotion) {
    const int w = 64, h = 48;
    ReprojectionFrame f = randomFrame(w, h, 21);
    f.color = positionColors(w, h);
    for (float& d : f.depth) d = 0.9f + 0.1f * d;  // view depths ~1..10 with these planes
    const glm::mat4 oldVP = viewProj(w, h, glm::vec3(0.0f), 0.0f);
    const glm::mat4 newVP = viewProj(w, h, glm::vec3(0.03f, 0.01f, 0.03f), -1.0f, 0.5f);
    const std::vector<glm::vec4> gpu = reprojectOnGpu(f, oldVP, newVP);
    size_t consistentPixels = 0, bad = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int s = sourceIndex(gpu[size_t(y * w + x)], w, h);
            if (s < 0 && ++bad <= 5) ADD_FAILURE() << "pixel " << x << "," << y << " shows no texel";
            if (s >= 0 && consistent(f, x, y, s, oldVP, newVP)) ++consistentPixels;
        }
    EXPECT_EQ(bad, 0u);
    EXPECT_GT(consistentPixels, size_t(w * h) / 4) << consistentPixels;
    EXPECT_LE(countDifferent(gpu, temporal::reprojectOnCpu(f, temporal::makeReprojection(oldVP, newVP))),
              size_t(w * h) / 200);
}

// Rays that meet no old surface in front of both cameras are dropped: turned away by 90 or 180
// degrees, nothing is found and every pixel keeps its own old colour. Without the view-depth test
// the points behind the new camera would project mirrored onto the screen.
TEST(TemporalReprojection, BehindAndOffScreenSourcesAreDropped) {
    const int w = 40, h = 30;
    const ReprojectionFrame f = randomFrame(w, h, 5);
    const glm::vec3 eye(0.0f);
    const glm::mat4 oldVP = viewProj(w, h, eye, 0.0f);
    for (float yaw : {180.0f, 90.0f, -90.0f}) {
        const glm::mat4 newVP = viewProj(w, h, eye, yaw);
        const temporal::Reprojection m = temporal::makeReprojection(oldVP, newVP);
        int behind = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec2 c = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(w), float(h)) * 2.0f - 1.0f;
                const temporal::Solution s = temporal::solveSource(c, f.depth[size_t(y * w + x)], w, h, m);
                const bool inside = s.window.x >= 0 && s.window.y >= 0 && s.window.x < w && s.window.y < h;
                EXPECT_FALSE(s.newViewDepth > 0.0f && inside) << x << "," << y;
                behind += s.newViewDepth > 0.0f ? 0 : 1;
            }
        if (yaw == 180.0f) EXPECT_EQ(behind, w * h);
        EXPECT_EQ(countDifferent(reprojectOnGpu(f, oldVP, newVP), f.color), 0u) << yaw;
    }
}

// A near red square over a far blue background; the camera slides left so the square moves 2 px
// right (and the far plane 0.2 px). The two columns it newly covers must show the square (the
// nearest source wins, found from the near seed although the old pixel there was blue); the two
// it uncovers are disoccluded and must show the background, not the square's stale colour.
TEST(TemporalReprojection, DisocclusionShowsTheBackground) {
    const int w = 64, h = 48;
    const glm::vec4 red(1, 0, 0, 1), blue(0, 0, 1, 1);
    const glm::mat4 oldVP = viewProj(w, h, glm::vec3(0.0f), 0.0f);
    const glm::vec4 squareClip = oldVP * glm::vec4(0, 0, -1, 1);  // view depth 1
    const float squareDepth = squareClip.z / squareClip.w * 0.5f + 0.5f;
    auto inSquare = [](int x, int y, int shift) { return x >= 24 + shift && x < 40 + shift && y >= 16 && y < 32; };
    ReprojectionFrame f{w, h, {}, {}};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            f.color.push_back(inSquare(x, y, 0) ? red : blue);
            f.depth.push_back(inSquare(x, y, 0) ? squareDepth : 1.0f);
        }
    // Pixels per unit at view depth 1: (h / 2) / tan(fov / 2).
    const float slide = 2.0f / (0.5f * float(h) / std::tan(glm::radians(kFovDeg) * 0.5f));
    const glm::mat4 newVP = viewProj(w, h, glm::vec3(-slide, 0.0f, 0.0f), 0.0f);
    const std::vector<glm::vec4> gpu = reprojectOnGpu(f, oldVP, newVP);
    size_t wrong = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec4 want = inSquare(x, y, 2) ? red : blue;
            if (gpu[size_t(y * w + x)] != want && ++wrong <= 5) ADD_FAILURE() << "pixel " << x << "," << y;
        }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(countDifferent(temporal::reprojectOnCpu(f, temporal::makeReprojection(oldVP, newVP)), gpu), 0u);
}

TEST(TemporalReprojection, GpuMatchesCpuAtOddSizesAndMotions) {
    for (auto [w, h] : {std::pair{1, 1}, std::pair{17, 1}, std::pair{37, 23}}) {
        const ReprojectionFrame f = randomFrame(w, h, 7);
        const glm::mat4 oldVP = viewProj(w, h, {0, 0, 0}, 0.0f);
        for (const glm::mat4& newVP : {viewProj(w, h, {0.05f, 0.0f, 0.0f}, 3.0f), viewProj(w, h, {0, 0.1f, 0.2f}, -6.0f, 4.0f)}) {
            const std::vector<glm::vec4> gpu = reprojectOnGpu(f, oldVP, newVP);
            const std::vector<glm::vec4> cpu = temporal::reprojectOnCpu(f, temporal::makeReprojection(oldVP, newVP));
            EXPECT_LE(countDifferent(gpu, cpu), size_t(w * h) / 100) << w << "x" << h;
        }
    }
}

namespace {

// A builtin scene's WBOIT composite and its nearest transparent depth (1 where none), GL order.
ReprojectionFrame renderedFrame(const test::TestScene& scene) {
    const Image image = scene.render("wboit").image;
    const CapturedFrame fragments = scene.capture();
    const int w = scene.width, h = scene.height;
    ReprojectionFrame f{w, h, std::vector<glm::vec4>(size_t(w * h)), std::vector<float>(size_t(w * h), 1.0f)};
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t gl = size_t((h - 1 - y) * w + x);  // Image and capture are top-first
            const float* p = image.pixel(x, y);
            f.color[gl] = glm::vec4(p[0], p[1], p[2], p[3]);
            for (const Fragment& frag : fragments.at(x, y)) f.depth[gl] = std::min(f.depth[gl], frag.depth);
        }
    }
    return f;
}

Image toImage(const std::vector<glm::vec4>& grid, int w, int h) {
    Image image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec4 c = grid[size_t((h - 1 - y) * w + x)];
            std::copy(&c.x, &c.x + 4, image.pixel(x, y));
        }
    return image;
}

}  // namespace

// A real render reprojected by a 10-degree orbit step (translation and rotation): GPU equals the CPU
// reference, and the result is clearly closer to a real render at the new camera than the stale
// frame is.
TEST(TemporalReprojection, RenderedSceneMatchesCpuAndBeatsTheStaleFrame) {
    const int w = 96, h = 72;
    const glm::vec3 background(0.9f, 0.85f, 0.8f);
    test::TestScene before(makeBuiltinScene("panes", 1), w, h, 20.0f, 15.0f, background);
    test::TestScene after(makeBuiltinScene("panes", 1), w, h, 30.0f, 15.0f, background);
    const ReprojectionFrame f = renderedFrame(before);
    auto vp = [](const test::TestScene& s) { return s.camera.projection(s.aspect()) * s.camera.view(); };
    const std::vector<glm::vec4> gpu = reprojectOnGpu(f, vp(before), vp(after));
    const std::vector<glm::vec4> cpu = temporal::reprojectOnCpu(f, temporal::makeReprojection(vp(before), vp(after)));
    EXPECT_LE(countDifferent(gpu, cpu, 1e-6f), size_t(w * h) / 200);

    const Image truth = after.render("wboit").image;
    const double stale = mseSrgb(truth, toImage(f.color, w, h));
    const double reprojected = mseSrgb(truth, toImage(gpu, w, h));
    EXPECT_GT(stale, 1e-4) << "the camera step should change the image";
    // Measured 0.51 (0.59 with the forward splat this replaced): the edges move right; what remains
    // is the parallax between the layers behind the nearest one, which a single-depth
    // reprojection cannot follow.
    EXPECT_LT(reprojected, 0.7 * stale) << "stale " << stale << " reprojected " << reprojected;
}

// ---- TemporalFrames: the facade the neural method calls ----

namespace {

// A camera's pinhole model in double precision, built from its position, target, up, field of
// view and clip planes (not from its matrices), for the round trip below.
struct PinholeD {
    glm::dvec3 eye, forward, right, up;
    double tanHalf, aspect, n, f;
    PinholeD(const Camera& c, double aspectRatio)
        : eye(c.position), forward(glm::normalize(glm::dvec3(c.target) - glm::dvec3(c.position))),
          right(glm::normalize(glm::cross(forward, glm::dvec3(c.up)))), up(glm::cross(right, forward)),
          tanHalf(std::tan(glm::radians(double(c.fovYDeg)) / 2)), aspect(aspectRatio), n(c.nearPlane), f(c.farPlane) {}
    // OpenGL's depth: NDC z = (f + n) / (f - n) - 2 f n / ((f - n) d) at distance d along the view axis.
    double ndcZ(double d) const { return (f + n) / (f - n) - 2 * f * n / ((f - n) * d); }
    double distance(double z) const { return 2 * f * n / ((f + n) - z * (f - n)); }
    glm::dvec3 unproject(glm::dvec3 ndc) const {
        return eye + distance(ndc.z) * (forward + ndc.x * tanHalf * aspect * right + ndc.y * tanHalf * up);
    }
    glm::dvec3 project(glm::dvec3 world, double* depth = nullptr) const {
        const glm::dvec3 rel = world - eye;
        const double d = glm::dot(rel, forward);
        if (depth) *depth = d;
        return {glm::dot(rel, right) / (d * tanHalf * aspect), glm::dot(rel, up) / (d * tanHalf), ndcZ(d)};
    }
};

}  // namespace

// The corrected and refresh frames' matrices (reprojection_math.hpp) are shared by the runtime and
// its CPU references, so GpuMatchesCpuReference cannot see them wrong (old and new cameras swapped
// would pass). Here they meet an independent double-precision world-space round trip: a pixel and
// depth unprojected with the new camera, projected with the old one (newToOld), and the other way
// round for the refresh frames' forward reprojection; sourceScale gives 1 / the old view depth.
TEST(ReprojectionMath, MatricesMatchADoubleWorldSpaceRoundTrip) {
    const double aspect = 16.0 / 9.0;
    Camera oldCam, newCam;
    oldCam.position = {0.4f, 0.9f, 4.0f};
    oldCam.target = {0.0f, 0.1f, 0.0f};
    oldCam.fovYDeg = 50.0f;
    oldCam.nearPlane = 0.3f;
    oldCam.farPlane = 12.0f;
    newCam = oldCam;
    newCam.position = {1.3f, 0.6f, 3.6f};  // moved and turned
    newCam.target = {0.3f, -0.1f, 0.2f};
    const glm::mat4 oldVP = oldCam.projection(float(aspect)) * oldCam.view();
    const glm::mat4 newVP = newCam.projection(float(aspect)) * newCam.view();
    const PinholeD oldD(oldCam, aspect), newD(newCam, aspect);
    const temporal::CorrectionMatrices m = temporal::makeCorrectionMatrices(oldVP, newVP);
    const temporal::Reprojection r = temporal::makeReprojection(oldVP, newVP);
    double worstXY = 0, worstZ = 0, worstScale = 0, worstForward = 0;
    int points = 0;
    for (double x : {-0.9, -0.3, 0.2, 0.8})
        for (double y : {-0.7, 0.0, 0.6})
            for (double dist : {0.6, 2.5, 7.0}) {
                // New camera's pixel at this view distance -> world -> old camera.
                const glm::dvec3 ndcNew(x, y, newD.ndcZ(dist));
                double oldDepth = 0;
                const glm::dvec3 want = oldD.project(newD.unproject(ndcNew), &oldDepth);
                const glm::vec4 h = m.newToOld * glm::vec4(glm::vec3(ndcNew), 1.0f);
                const glm::dvec3 got = glm::dvec3(glm::vec3(h) / h.w);
                worstXY = std::max({worstXY, std::abs(got.x - want.x), std::abs(got.y - want.y)});
                worstZ = std::max(worstZ, std::abs(got.z - want.z));
                // sourceScale . (old NDC, 1) = 1 / old view depth.
                const double scale = glm::dot(glm::dvec4(m.sourceScale), glm::dvec4(want, 1.0));
                worstScale = std::max(worstScale, std::abs(scale * oldDepth - 1.0));
                EXPECT_EQ(r.sourceScale, m.sourceScale);
                // The refresh frames' forward map (rows 0, 1, 3 of R): old NDC -> new NDC x, y.
                const glm::dvec4 v(want, 1.0);
                const double w = glm::dot(glm::dvec4(r.row3), v);
                worstForward = std::max({worstForward, std::abs(glm::dot(glm::dvec4(r.row0), v) / w - x),
                                         std::abs(glm::dot(glm::dvec4(r.row1), v) / w - y)});
                ++points;
            }
    // float matrices against double: about 1e-6 here; old and new swapped moves points by ~0.1-1.
    EXPECT_LT(worstXY, 1e-4) << points << " points";
    EXPECT_LT(worstZ, 1e-4);
    EXPECT_LT(worstScale, 1e-4);
    EXPECT_LT(worstForward, 1e-4);
}

TEST(TemporalFrames, FixedTwoAlternatesAndKeepsItsOwnCopy) {
    test::glContext();
    const int w = 21, h = 13;
    MethodOptions options;
    options.neural.temporalMode = NeuralOptions::TemporalMode::Warp;  // these tests check the warp path
    options.neural.temporalInterval = 2;
    TemporalFrames temporal(options);
    const ReprojectionFrame first = randomFrame(w, h, 1), second = randomFrame(w, h, 2);
    gl::Texture2D composite = uploadColor(first), depth = uploadDepth(first), output(GL_RGBA32F, w, h);
    const glm::mat4 vp = viewProj(w, h, {0, 0, 0}, 10.0f);

    ASSERT_TRUE(temporal.beginFrame(w, h));
    EXPECT_FALSE(temporal.lastWasInterpolated());
    EXPECT_THROW(temporal.interpolate(vp, {}, glm::vec3(1.0f), output.id()), Error);  // a real frame is not interpolated
    temporal.endRealFrame(composite.id(), {.nearestDepth = depth.id()}, vp, w, h);
    EXPECT_EQ(temporal.interval(), 2);
    // The method overwrites its targets: the kept copy must not change.
    starnt::gl::uploadTexture(composite.id(), w, h, GL_RGBA, GL_FLOAT, second.color.data());

    ASSERT_FALSE(temporal.beginFrame(w, h));
    EXPECT_TRUE(temporal.lastWasInterpolated());
    EXPECT_THROW(temporal.endRealFrame(composite.id(), {.nearestDepth = depth.id()}, vp, w, h), Error);
    gl::GpuPassTimer timer(true);
    EXPECT_EQ(temporal.interpolatedPasses(), TemporalFrames::Passes::None);
    temporal.interpolate(vp, {}, glm::vec3(1.0f), output.id(), &timer);
    EXPECT_EQ(countDifferent(download(output.id(), w, h), first.color), 0u);
    EXPECT_EQ(timer.collect().count("reproject"), 1u);

    EXPECT_TRUE(temporal.beginFrame(w, h));
    // 16 (colour) + 4 (depth) bytes per pixel, 2 x 8 (min, max) per 8x8 block (3 x 2 blocks).
    EXPECT_EQ(temporal.gpuMemoryBytes(), size_t(w * h) * 20 + 6 * 16);
}

TEST(TemporalFrames, SizeChangeAndResetForceARealFrame) {
    test::glContext();
    MethodOptions options;
    options.neural.temporalMode = NeuralOptions::TemporalMode::Warp;  // these tests check the warp path
    options.neural.temporalInterval = 4;
    TemporalFrames temporal(options);
    const ReprojectionFrame f = randomFrame(8, 8, 3);
    gl::Texture2D composite = uploadColor(f), depth = uploadDepth(f);
    ASSERT_TRUE(temporal.beginFrame(8, 8));
    temporal.endRealFrame(composite.id(), {.nearestDepth = depth.id()}, glm::mat4(1.0f), 8, 8);
    EXPECT_FALSE(temporal.beginFrame(8, 8));
    EXPECT_TRUE(temporal.beginFrame(9, 8)) << "a resized frame cannot be reprojected";
    // That real frame never ended (e.g. it threw): nothing is kept, so the next one is real too.
    EXPECT_TRUE(temporal.beginFrame(8, 8));
    temporal.endRealFrame(composite.id(), {.nearestDepth = depth.id()}, glm::mat4(1.0f), 8, 8);
    EXPECT_FALSE(temporal.beginFrame(8, 8));
    temporal.reset();
    EXPECT_TRUE(temporal.beginFrame(8, 8));
    EXPECT_TRUE(temporal.beginFrame(8, 8)) << "nothing kept since the reset";
}

TEST(TemporalFrames, IntervalOneKeepsNothing) {
    test::glContext();
    TemporalFrames temporal(MethodOptions{});
    const ReprojectionFrame f = randomFrame(8, 8, 6);
    gl::Texture2D composite = uploadColor(f), depth = uploadDepth(f);
    EXPECT_FALSE(temporal.interpolates());
    for (int i = 0; i < 3; ++i) {
        ASSERT_TRUE(temporal.beginFrame(8, 8));
        temporal.endRealFrame(composite.id(), {.nearestDepth = depth.id()}, glm::mat4(1.0f), 8, 8);
    }
    EXPECT_EQ(temporal.gpuMemoryBytes(), 0u);
    MethodOptions bad;
    bad.neural.temporalInterval = kMaxTemporalInterval + 1;
    EXPECT_THROW(TemporalFrames{bad}, Error);
}

TEST(TemporalFrames, AutoMeasuresRealFramesAndRaisesTheInterval) {
    test::glContext();
    const ReprojectionFrame f = randomFrame(16, 16, 4);
    gl::Texture2D composite = uploadColor(f), depth = uploadDepth(f), output(GL_RGBA32F, 16, 16);
    auto run = [&](double targetFps) {
        MethodOptions options;
        options.neural.temporalMode = NeuralOptions::TemporalMode::Warp;  // these tests check the warp path
        options.neural.temporalAuto = true;
        options.neural.targetFps = targetFps;
        TemporalFrames temporal(options);
        std::string pattern;
        for (int i = 0; i < 7; ++i) {
            const bool real = temporal.beginFrame(16, 16);
            pattern += real ? 'R' : 'i';
            if (real) temporal.endRealFrame(composite.id(), {.nearestDepth = depth.id()}, glm::mat4(1.0f), 16, 16);
            else temporal.interpolate(glm::mat4(1.0f), {}, glm::vec3(1.0f), output.id());
        }
        EXPECT_GT(temporal.averageRealFrameMs(), 0.0);
        // Interpolated frames are timed too (auto weighs their cost); none ran at 10^9 fps.
        if (pattern.find('i') != std::string::npos) EXPECT_GT(temporal.averageInterpolatedFrameMs(), 0.0);
        else EXPECT_EQ(temporal.averageInterpolatedFrameMs(), 0.0);
        return pattern;
    };
    // Any real frame beats one frame per 1000 s: 4 after the first measurement (taken at frame 2).
    EXPECT_EQ(run(1e-3), "RRiiiRi");
    // No frame reaches 10^9 fps: plain rendering.
    EXPECT_EQ(run(1e9), "RRRRRRR");
}

// Reprojection time at 1280x720 (not a check; run with STARNT_TEMPORAL_TIMING=1). Two frames: a
// plausible one (far background above, a smooth slanted surface below, the camera moving a little
// per frame) and a worst case (random depth per pixel: a point cloud, holes everywhere).
TEST(TemporalFrames, TimingAt720p) {
    if (!std::getenv("STARNT_TEMPORAL_TIMING")) GTEST_SKIP() << "set STARNT_TEMPORAL_TIMING=1 to measure";
    test::glContext();
    const int w = 1280, h = 720;
    ReprojectionFrame smooth = randomFrame(w, h, 9);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) smooth.depth[size_t(y * w + x)] = y < h / 2 ? 0.9f + 0.09f * float(y) / float(h) : 1.0f;
    for (const auto& [name, frame] : {std::pair<const char*, const ReprojectionFrame*>{"smooth", &smooth}, {"random depth", nullptr}}) {
        const ReprojectionFrame f = frame ? *frame : randomFrame(w, h, 9);
        gl::Texture2D composite = uploadColor(f), depth = uploadDepth(f), output(GL_RGBA32F, w, h);
        MethodOptions options;
    options.neural.temporalMode = NeuralOptions::TemporalMode::Warp;  // these tests check the warp path
        options.neural.temporalInterval = 4;
        TemporalFrames temporal(options);
        gl::GpuPassTimer timer(gl::currentContextIsSoftware());
        std::vector<double> capture, reproject;
        for (int i = 0; i < 12; ++i) {
            const glm::mat4 vp = viewProj(w, h, {0.01f * float(i), 0.0f, 0.0f}, 0.25f * float(i));
            if (temporal.beginFrame(w, h)) {
                glFinish();
                const auto t0 = std::chrono::steady_clock::now();
                temporal.endRealFrame(composite.id(), {.nearestDepth = depth.id()}, vp, w, h);
                glFinish();
                capture.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            } else {
                EXPECT_EQ(temporal.interpolatedPasses(), TemporalFrames::Passes::None);
    temporal.interpolate(vp, {}, glm::vec3(1.0f), output.id(), &timer);
                reproject.push_back(timer.collect()["reproject"]);
            }
        }
        std::sort(capture.begin(), capture.end());
        std::sort(reproject.begin(), reproject.end());
        std::printf("1280x720 %s: capture median %.1f ms, reproject median %.1f ms (min %.1f, max %.1f) over %zu frames\n",
                    name, capture[capture.size() / 2], reproject[reproject.size() / 2], reproject.front(),
                    reproject.back(), reproject.size());
    }
}
