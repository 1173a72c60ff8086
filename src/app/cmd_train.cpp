#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

#include "app/commands.hpp"
#include "reference/training_data.hpp"
#include "starnt/error.hpp"
#include "starnt/gl_context.hpp"
#include "starnt/scene.hpp"
#include "starnt/train.hpp"

namespace starnt::app {
namespace {

void progressBar(const char* label, double fraction, const std::string& suffix) {
    const int width = 30;
    const int filled = int(fraction * width + 0.5);
    std::fprintf(stderr, "\r%-10s [%.*s%*s] %3d%% %s", label, filled, "##############################", width - filled, "",
                 int(fraction * 100.0 + 0.5), suffix.c_str());
    std::fflush(stderr);
}

// Training takes minutes: check --out first (a .json file in an existing folder we can write).
void checkWeightsOutput(const std::string& out) {
    namespace fs = std::filesystem;
    std::string ext = fs::path(out).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".json") throw Error("--out " + out + ": a weights file must be a .json file");
    std::error_code ec;
    if (fs::is_directory(out, ec)) throw Error("--out " + out + ": is a directory");
    const fs::path dir = fs::path(out).parent_path().empty() ? fs::path(".") : fs::path(out).parent_path();
    if (!fs::is_directory(dir, ec)) throw Error("--out " + out + ": folder " + dir.string() + " does not exist");
    const std::string probe = out + ".tmp-probe-" + std::to_string(::getpid());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) throw Error("--out " + out + ": cannot write in folder " + dir.string() + ": " + std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

}  // namespace

void addTrainCommand(CLI::App& app) {
    struct Args {
        std::string network, out;
        uint64_t samples = 10'000'000, seed = 1, synthetic = 300'000;
        std::vector<std::string> scenes;
        int captureWidth = 96, captureHeight = 72;
    };
    auto a = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand("train", "train the STAR-NT or DFAOIT network and write a weights file");
    cmd->add_option("--network", a->network, "starnt|dfaoit")->required();
    cmd->add_option("--out", a->out, "weights file to write (.json)")->required();
    cmd->add_option("--samples", a->samples, "training samples seen in total")->capture_default_str();
    cmd->add_option("--seed", a->seed, "random seed (weights, split, synthetic data)")->capture_default_str();
    cmd->add_option("--synthetic", a->synthetic, "synthetic fragment lists added to the captured ones")->capture_default_str();
    cmd->add_option("--scenes", a->scenes, "built-in scenes to capture (builtin:NAME; default: all built-ins)");
    cmd->add_option("--capture-width", a->captureWidth, "capture resolution width")->capture_default_str();
    cmd->add_option("--capture-height", a->captureHeight, "capture resolution height")->capture_default_str();
    cmd->callback([a] {
        const nn::NetworkKind kind = nn::parseKind(a->network);
        checkWeightsOutput(a->out);
        if (a->samples < 1000 || a->samples > 10'000'000'000ull) throw Error("--samples must be in 1000..1e10");
        if (a->captureWidth < 8 || a->captureHeight < 8 || a->captureWidth > 1024 || a->captureHeight > 1024) {
            throw Error("--capture-width/--capture-height must be in 8..1024");
        }
        CaptureSetOptions capture;
        capture.width = a->captureWidth;
        capture.height = a->captureHeight;
        if (!a->scenes.empty()) {
            capture.scenes.clear();
            for (const std::string& s : a->scenes) {
                if (s.rfind("builtin:", 0) != 0) {
                    throw Error("--scenes " + s + ": training uses built-in scenes only (builtin:NAME); the suite "
                                "scene files are held out for evaluation");
                }
                makeBuiltinScene(s.substr(8), 1);  // validates the name
                capture.scenes.push_back(s.substr(8));
            }
        }
        const auto t0 = std::chrono::steady_clock::now();
        HeadlessGlContext context;
        capture.progress = [](size_t done, size_t total) {
            progressBar("capture", double(done) / double(total), std::to_string(done) + "/" + std::to_string(total));
        };
        std::vector<FragmentList> lists = captureTrainingLists(capture);
        std::fprintf(stderr, "\n");
        const size_t captured = lists.size();
        auto synthetic = nn::syntheticFragmentLists(a->synthetic, a->seed);
        lists.insert(lists.end(), std::make_move_iterator(synthetic.begin()), std::make_move_iterator(synthetic.end()));
        nn::TrainingSet set = nn::buildTrainingSet(kind, lists);
        std::fprintf(stderr, "training set: %zu samples (%zu captured pixel lists, %llu synthetic lists)\n", set.size(),
                     captured, (unsigned long long)a->synthetic);
        nn::TrainOptions options;
        options.samples = a->samples;
        options.seed = a->seed;
        options.progress = [](double p, double loss) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "loss %.3e", loss);
            progressBar("train", p, buf);
        };
        nn::Network net = nn::train(kind, set, options);
        std::fprintf(stderr, "\n");
        nn::saveWeights(net, a->out);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("%s network: validation MSE %.4e after %llu samples (%.1f s) -> %s\n", nn::kindName(kind),
                    net.validationMse, (unsigned long long)net.trainingSamples, seconds, a->out.c_str());
    });
}

}  // namespace starnt::app
