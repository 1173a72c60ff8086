#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "starnt/error.hpp"
#include "starnt/tools/image.hpp"
#include "test_support.hpp"

using namespace starnt;
namespace fs = std::filesystem;

namespace {

Image randomImage(int w, int h, unsigned seed, float lo = 0.0f, float hi = 1.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    Image img(w, h);
    for (float& v : img.rgba) v = u(rng);
    return img;
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void writeFile(const fs::path& p, const std::string& s) {
    std::ofstream out(p, std::ios::binary);
    out << s;
}

// Expects loadImage(path) to throw starnt::Error whose message names the path.
void expectLoadError(const fs::path& path) {
    try {
        loadImage(path.string());
        ADD_FAILURE() << "expected starnt::Error for " << path;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
}

size_t entryCount(const fs::path& dir) {
    return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST(Srgb, TransferFunctionsMatchStandardValues) {
    EXPECT_FLOAT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_EQ(linearToSrgb(1.0f), 1.0f);
    EXPECT_NEAR(linearToSrgb(0.5f), 0.7353570f, 1e-6);
    EXPECT_NEAR(linearToSrgb(0.001f), 0.01292f, 1e-7);  // linear segment
    EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-5);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-6);
    EXPECT_NEAR(srgbToLinear(0.04f), 0.04f / 12.92f, 1e-9);
    EXPECT_EQ(srgbToLinear(1.0f), 1.0f);
    EXPECT_EQ(linearToSrgb(-0.5f), 0.0f);
    EXPECT_GT(linearToSrgb(2.0f), 1.0f);  // no clamping above 1
    for (int i = 0; i <= 255; ++i) {
        const float e = float(i) / 255.0f;
        EXPECT_NEAR(linearToSrgb(srgbToLinear(e)), e, 2e-6) << i;
    }
}

TEST(ImageIo, PngRoundTripWithinHalfAnSrgbStep) {
    const fs::path dir = test::makeTempDir("png_rt");
    const Image img = randomImage(23, 17, 3, -0.2f, 1.2f);
    const std::string path = (dir / "a.png").string();
    savePng(img, path);
    const Image back = loadImage(path);
    ASSERT_EQ(back.width, 23);
    ASSERT_EQ(back.height, 17);
    for (size_t i = 0; i < img.rgba.size(); ++i) {
        const float want = std::clamp(img.rgba[i], 0.0f, 1.0f);
        if (i % 4 == 3)
            ASSERT_NEAR(back.rgba[i], want, 0.5f / 255.0f + 1e-6f) << i;
        else
            ASSERT_NEAR(linearToSrgb(back.rgba[i]), linearToSrgb(want), 0.5f / 255.0f + 1e-6f) << i;
    }
    EXPECT_EQ(entryCount(dir), 1u);  // no temporary file left
    fs::remove_all(dir);
}

TEST(ImageIo, PngTopRowIsFirst) {
    const fs::path dir = test::makeTempDir("png_orient");
    Image img(2, 2, 0.0f);
    img.pixel(1, 0)[0] = 1.0f;  // top right red
    img.pixel(0, 1)[2] = 1.0f;  // bottom left blue
    for (int i = 0; i < 4; ++i) img.rgba[size_t(i) * 4 + 3] = 1.0f;
    const std::string path = (dir / "o.png").string();
    saveImage(img, path);
    const Image back = loadImage(path);
    EXPECT_EQ(back.pixel(1, 0)[0], 1.0f);
    EXPECT_EQ(back.pixel(0, 1)[2], 1.0f);
    EXPECT_EQ(back.pixel(0, 0)[0], 0.0f);
    fs::remove_all(dir);
}

TEST(ImageIo, ExrRoundTripIsExact) {
    const fs::path dir = test::makeTempDir("exr_rt");
    Image img = randomImage(19, 11, 5, -3.0f, 40.0f);
    img.rgba[0] = 1e-8f;
    img.rgba[1] = 123456.789f;
    const std::string path = (dir / "a.EXR").string();  // extension matching ignores case
    saveImage(img, path);
    const Image back = loadImage(path);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    ASSERT_EQ(back.rgba, img.rgba);
    EXPECT_EQ(entryCount(dir), 1u);
    fs::remove_all(dir);
}

TEST(ImageIo, LoadFailuresThrowNamingThePath) {
    const fs::path dir = test::makeTempDir("load_fail");
    expectLoadError(dir / "missing.png");
    expectLoadError(dir / "missing.exr");

    // Truncated PNG: a valid file cut in half.
    const fs::path good = dir / "good.png";
    savePng(randomImage(64, 64, 11), good.string());
    const std::string bytes = readFile(good);
    ASSERT_GT(bytes.size(), 100u);
    writeFile(dir / "truncated.png", bytes.substr(0, bytes.size() / 2));
    expectLoadError(dir / "truncated.png");

    writeFile(dir / "text.png", "this is not an image\n");
    expectLoadError(dir / "text.png");
    writeFile(dir / "text.exr", "this is not an image either\n");
    expectLoadError(dir / "text.exr");
    writeFile(dir / "empty.png", "");
    expectLoadError(dir / "empty.png");

    // Unknown extension, even for a valid PNG's bytes.
    writeFile(dir / "image.bmp", bytes);
    expectLoadError(dir / "image.bmp");
    writeFile(dir / "noextension", bytes);
    expectLoadError(dir / "noextension");
    fs::remove_all(dir);
}

TEST(ImageIo, SaveIntoMissingFolderThrowsAndLeavesNothing) {
    const fs::path dir = test::makeTempDir("save_missing");
    const fs::path missing = dir / "no_such_folder";
    const Image img = randomImage(4, 4, 1);
    EXPECT_THROW(savePng(img, (missing / "a.png").string()), Error);
    EXPECT_THROW(saveExr(img, (missing / "a.exr").string()), Error);
    EXPECT_THROW(writeFileAtomic((missing / "a.txt").string(), "x"), Error);
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_EQ(entryCount(dir), 0u);
    fs::remove_all(dir);
}

TEST(ImageIo, SaveOverExistingFileReplacesItWhole) {
    const fs::path dir = test::makeTempDir("save_over");
    const fs::path path = dir / "a.png";
    writeFile(path, std::string(200000, 'x'));  // much longer than the PNG to come
    const Image img = randomImage(8, 8, 2);
    savePng(img, path.string());
    EXPECT_LT(fs::file_size(path), 200000u);
    const Image back = loadImage(path.string());
    EXPECT_EQ(back.width, 8);
    EXPECT_EQ(entryCount(dir), 1u);

    // Same for an EXR replaced by a smaller EXR.
    const fs::path exr = dir / "b.exr";
    saveExr(randomImage(64, 64, 3), exr.string());
    const Image small = randomImage(2, 3, 4);
    saveExr(small, exr.string());
    EXPECT_EQ(loadImage(exr.string()).rgba, small.rgba);
    EXPECT_EQ(entryCount(dir), 2u);
    fs::remove_all(dir);
}

TEST(ImageIo, WriteFileAtomicWritesExactBytesAndCleansUpOnFailure) {
    const fs::path dir = test::makeTempDir("atomic");
    std::string contents("binary\0data\nwith zero", 21);
    const fs::path path = dir / "f.bin";
    writeFileAtomic(path.string(), contents);
    EXPECT_EQ(readFile(path), contents);
    writeFileAtomic(path.string(), "short");
    EXPECT_EQ(readFile(path), "short");

    // Renaming onto a non-empty directory fails: the temporary file must be removed.
    const fs::path blocker = dir / "blocker";
    fs::create_directories(blocker / "inside");
    EXPECT_THROW(writeFileAtomic(blocker.string(), "data"), Error);
    EXPECT_TRUE(fs::is_directory(blocker));
    EXPECT_EQ(entryCount(dir), 2u);  // f.bin and blocker only
    fs::remove_all(dir);
}

TEST(ImageIo, RejectsEmptyImagesAndUnknownExtensions) {
    const fs::path dir = test::makeTempDir("save_reject");
    EXPECT_THROW(savePng(Image(0, 5), (dir / "a.png").string()), Error);
    EXPECT_THROW(saveExr(Image(5, 0), (dir / "a.exr").string()), Error);
    EXPECT_THROW(saveImage(Image(0, 0), (dir / "a.png").string()), Error);
    EXPECT_THROW(saveImage(Image(2, 2), (dir / "a.jpg").string()), Error);
    EXPECT_THROW(saveImage(Image(2, 2), (dir / "a").string()), Error);
    EXPECT_EQ(entryCount(dir), 0u);
    fs::remove_all(dir);
}
