#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "train/training_data.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/families.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/scene.hpp"
#include "starnt/tools/train.hpp"

namespace starnt::app {
namespace {

void progressBar(const char* label, double fraction, const std::string& suffix) {
    const int width = 30;
    const int filled = int(fraction * width + 0.5);
    std::fprintf(stderr, "\r%-10s [%.*s%*s] %3d%% %s", label, filled, "##############################", width - filled, "",
                 int(fraction * 100.0 + 0.5), suffix.c_str());
    std::fflush(stderr);
}

// Training takes minutes: check the outputs first (a .json file in an existing folder we can write).
// `flag` names the option and `what` the file in the messages.
void checkJsonOutput(const std::string& flag, const std::string& what, const std::string& out) {
    namespace fs = std::filesystem;
    std::string ext = fs::path(out).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".json") throw Error(flag + " " + out + ": " + what + " must be a .json file");
    std::error_code ec;
    if (fs::is_directory(out, ec)) throw Error(flag + " " + out + ": is a directory");
    const fs::path dir = fs::path(out).parent_path().empty() ? fs::path(".") : fs::path(out).parent_path();
    if (!fs::is_directory(dir, ec)) throw Error(flag + " " + out + ": folder " + dir.string() + " does not exist");
    const std::string probe = out + ".tmp-probe-" + std::to_string(::getpid());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) throw Error(flag + " " + out + ": cannot write in folder " + dir.string() + ": " + std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

// Procedural families named by --families (comma-separated names or "all"), in the project's
// order whatever the order given, so that the training set does not depend on how they are listed.
std::vector<std::string> parseFamilyList(const std::string& text) {
    if (text.empty()) return {};
    if (text == "all") return nn::proceduralFamilyNames();
    std::vector<std::string> named;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string name = text.substr(start, comma - start);
        if (!nn::isProceduralFamily(name)) nn::proceduralFamilyLists(name, 0, 0);  // throws, naming the valid ones
        named.push_back(name);
        start = comma + 1;
    }
    std::vector<std::string> ordered;
    for (const std::string& name : nn::proceduralFamilyNames()) {
        if (std::find(named.begin(), named.end(), name) != named.end()) ordered.push_back(name);
    }
    return ordered;
}

// Validation captures of a built-in family: another scene seed and other cameras than training.
std::vector<FragmentList> captureValidationLists(const std::string& scene, int width, int height) {
    CaptureSetOptions o;
    o.scenes = {scene};
    o.seeds = {31};
    o.azimuths = {40.0f, 200.0f};
    o.elevations = {10.0f};
    o.alphaOverrides = {-1.0f, 0.3f};
    o.width = width;
    o.height = height;
    return captureTrainingLists(o);
}

// Seeds of the procedural families' validation lists: never the training stream.
constexpr uint64_t kValidationSeedOffset = 1'000'003;

struct TrainArgs {
    std::string network, out, families, holdOut, report, weighting = "none";
    // samples 0: the network's recipe (nn::recipeOptions).
    uint64_t samples = 0, seed = 1, synthetic = 300'000, familyLists = 50'000, validationLists = 20'000;
    std::vector<std::string> scenes;
    int captureWidth = 96, captureHeight = 72;
    float learningRate = 0.0f;  // 0: the network's recipe
    bool samplesGiven = false, learningRateGiven = false;  // on the command line (an explicit 0 is no recipe)
};

// What the arguments resolve to, checked before minutes of capture and training.
struct TrainPlan {
    nn::NetworkKind kind = nn::NetworkKind::StarNT;
    CaptureSetOptions capture;
    nn::SampleWeighting weighting = nn::SampleWeighting::None;
    std::vector<std::string> procedural;  // procedural families to train on
    bool reportFamilies = false;          // per-family errors printed (and written with --report)
};

TrainPlan checkTrainArgs(const TrainArgs& a) {
    TrainPlan plan;
    plan.kind = nn::parseKind(a.network);
    checkJsonOutput("--out", "a weights file", a.out);
    if (!a.report.empty()) checkJsonOutput("--report", "the report", a.report);
    if ((a.samples != 0 || a.samplesGiven) && (a.samples < 1000 || a.samples > 10'000'000'000ull)) throw Error("--samples must be in 1000..1e10");
    if ((a.learningRate != 0.0f || a.learningRateGiven) && !(a.learningRate > 0.0f && a.learningRate <= 1.0f)) {
        throw Error("--learning-rate must be in (0, 1]");
    }
    if (a.captureWidth < 8 || a.captureHeight < 8 || a.captureWidth > 1024 || a.captureHeight > 1024) {
        throw Error("--capture-width/--capture-height must be in 8..1024");
    }
    if (a.familyLists > 10'000'000 || a.validationLists < 1 || a.validationLists > 10'000'000) {
        throw Error("--family-lists must be in 0..1e7 and --validation-lists in 1..1e7");
    }
    CaptureSetOptions& capture = plan.capture;
    capture.width = a.captureWidth;
    capture.height = a.captureHeight;
    if (!a.scenes.empty()) {
        capture.scenes.clear();
        for (const std::string& s : a.scenes) {
            if (s.rfind("builtin:", 0) != 0) {
                throw Error("--scenes " + s + ": training uses built-in scenes only (builtin:NAME); the suite "
                            "scene files are held out for evaluation");
            }
            makeBuiltinScene(s.substr(8), 1);  // validates the name
            capture.scenes.push_back(s.substr(8));
        }
    }
    if (a.weighting != "none" && a.weighting != "tail-visibility") {
        throw Error("--weighting " + a.weighting + ": expected none or tail-visibility");
    }
    plan.weighting =
        a.weighting == "none" ? nn::SampleWeighting::None : nn::SampleWeighting::TailVisibility;
    plan.procedural =
        parseFamilyList(a.families.empty() && !a.holdOut.empty() ? "all" : a.families);
    // Check the held-out name before minutes of capture: a captured scene or a procedural family.
    std::vector<std::string> familyNames = capture.scenes;
    familyNames.insert(familyNames.end(), plan.procedural.begin(), plan.procedural.end());
    nn::checkHoldOut(familyNames, a.holdOut);
    plan.reportFamilies = !a.holdOut.empty() || !plan.procedural.empty() || !a.report.empty();
    return plan;
}

// Captures the built-in scenes and makes the procedural families: the training families, each with
// its validation lists when they are reported.
std::vector<nn::TrainingFamily> trainingFamilies(const TrainArgs& a, const TrainPlan& plan) {
    std::vector<nn::TrainingFamily> families;
    HeadlessGlContext context;
    // One capture per scene, in the order of capture.scenes: concatenated, the same lists in
    // the same order as one capture of all of them (the shipped weights depend on that order).
    CaptureSetOptions capture = plan.capture;
    const std::vector<std::string> scenes = capture.scenes;
    size_t done = 0;
    const size_t total = scenes.size() * capture.seeds.size() * capture.azimuths.size() * capture.elevations.size() *
                         capture.alphaOverrides.size();
    for (const std::string& scene : scenes) {
        capture.scenes = {scene};
        const size_t before = done;
        capture.progress = [&](size_t d, size_t) {
            done = before + d;
            progressBar("capture", double(done) / double(total), std::to_string(done) + "/" + std::to_string(total));
        };
        nn::TrainingFamily family{scene, captureTrainingLists(capture), {}};
        if (plan.reportFamilies) family.validation = captureValidationLists(scene, a.captureWidth, a.captureHeight);
        families.push_back(std::move(family));
    }
    std::fprintf(stderr, "\n");
    for (const std::string& name : plan.procedural) {
        families.push_back({name, nn::proceduralFamilyLists(name, a.familyLists, a.seed),
                            nn::proceduralFamilyLists(name, a.validationLists, a.seed + kValidationSeedOffset)});
    }
    return families;
}

// Trains on the families (the held-out one left out) and the synthetic lists, writes the weights.
// `t0`: when the run began (the time printed includes the capture).
nn::Network trainAndSave(const TrainArgs& a, const TrainPlan& plan, const std::vector<nn::TrainingFamily>& families,
                         std::chrono::steady_clock::time_point t0) {
    const auto synthetic = nn::syntheticFragmentLists(a.synthetic, a.seed);
    nn::TrainingSet set = nn::buildFamilyTrainingSet(plan.kind, families, a.holdOut, synthetic, plan.weighting);
    std::string composition;
    for (const nn::TrainingFamily& f : families) {
        composition += " " + f.name + " " + (f.name == a.holdOut ? "held out" : std::to_string(f.train.size()));
    }
    std::fprintf(stderr, "training set: %zu samples (lists per family:%s; %llu synthetic lists)\n", set.size(),
                 composition.c_str(), (unsigned long long)a.synthetic);
    nn::TrainOptions options = nn::recipeOptions(plan.kind);
    if (a.samples != 0) options.samples = a.samples;
    if (a.learningRate != 0.0f) options.learningRate = a.learningRate;
    options.seed = a.seed;
    options.progress = [](double p, double loss) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "loss %.3e", loss);
        progressBar("train", p, buf);
    };
    nn::Network net = nn::train(plan.kind, set, options);
    std::fprintf(stderr, "\n");
    nn::saveWeights(net, a.out);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%s network: validation MSE %.4e after %llu samples (%.1f s) -> %s\n", nn::kindName(plan.kind),
                net.validationMse, (unsigned long long)net.trainingSamples, seconds, a.out.c_str());
    return net;
}

// Per-family validation errors of `net` beside hybrid, hybrid-moments and WBOIT, printed and
// (with --report) written.
void reportFamilies(const TrainArgs& a, const nn::Network& net, const std::vector<nn::TrainingFamily>& families) {
    // Per-family image-space errors on lists never trained on (composite over black vs exact).
    nlohmann::json report = {{"network", nn::kindName(net.kind)}, {"held_out", a.holdOut},
                             {"samples", net.trainingSamples},     {"seed", a.seed}, {"weighting", a.weighting},
                             {"families", nlohmann::json::array()}};
    // Whole family (every covered pixel), then its tail pixels (N > 3) alone.
    std::printf("%-10s %-9s %7s %10s %10s %10s %10s %9s %7s %10s %10s %10s %9s\n", "family", "trained", "pixels",
                nn::kindName(net.kind), "hybrid", "hyb-mom", "wboit", "net/wboit", "tail", "net tail", "hyb tail",
                "wb tail", "tail n/w");
    for (const nn::TrainingFamily& f : families) {
        const nn::FamilyErrors e = nn::familyErrors(net, f.validation);
        const bool heldOut = f.name == a.holdOut;
        std::printf("%-10s %-9s %7zu %10.3e %10.3e %10.3e %10.3e %9.3f %7zu %10.3e %10.3e %10.3e %9.3f\n",
                    f.name.c_str(), heldOut ? "HELD-OUT" : f.train.empty() ? "no" : "yes", e.pixels, e.network,
                    e.hybrid, e.hybridMoments, e.wboit,
                    e.wboit > 0.0 ? e.network / e.wboit : 0.0, e.tailPixels, e.networkTail, e.hybridTail,
                    e.wboitTail, e.wboitTail > 0.0 ? e.networkTail / e.wboitTail : 0.0);
        report["families"].push_back({{"family", f.name},
                                      {"held_out", heldOut},
                                      {"captured", !nn::isProceduralFamily(f.name)},
                                      {"training_lists", heldOut ? 0 : f.train.size()},
                                      {"validation_pixels", e.pixels},
                                      {"validation_tail_pixels", e.tailPixels},
                                      {"mse_network", e.network},
                                      {"mse_hybrid", e.hybrid},
                                      {"mse_hybrid_moments", e.hybridMoments},
                                      {"mse_wboit", e.wboit},
                                      {"tail_mse_network", e.networkTail},
                                      {"tail_mse_hybrid", e.hybridTail},
                                      {"tail_mse_wboit", e.wboitTail}});
    }
    if (!a.report.empty()) {
        // Under a temporary name, renamed when complete: a failed write leaves no partial report.
        const std::string temporary = a.report + ".tmp-" + std::to_string(::getpid());
        {
            std::ofstream out(temporary);
            out << report.dump(1) << "\n";
            if (!out) {
                std::filesystem::remove(temporary);
                throw Error("--report " + a.report + ": cannot write");
            }
        }
        std::filesystem::rename(temporary, a.report);
    }
}

void runTrain(const TrainArgs& a) {
    const TrainPlan plan = checkTrainArgs(a);
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<nn::TrainingFamily> families = trainingFamilies(a, plan);
    const nn::Network net = trainAndSave(a, plan, families, t0);
    if (plan.reportFamilies) reportFamilies(a, net, families);
}

}  // namespace

void addTrainCommand(CLI::App& app) {
    auto args = std::make_shared<TrainArgs>();
    TrainArgs& a = *args;
    CLI::App* cmd = app.add_subcommand("train", "train the STAR-NT (or its residual or depth kind) or DFAOIT network and write a weights file");
    cmd->add_option("--network", a.network, "starnt|starnt-residual|starnt-d|dfaoit")->required();
    cmd->add_option("--out", a.out, "weights file to write (.json)")->required();
    cmd->add_option("--samples", a.samples, "training samples seen in total (default: 10000000; dfaoit 30000000)");
    cmd->add_option("--learning-rate", a.learningRate, "Adam's initial step size, cosine-decayed (default: 1e-3; dfaoit 3e-3)");
    cmd->add_option("--seed", a.seed, "random seed (weights, split, synthetic data)")->capture_default_str();
    cmd->add_option("--synthetic", a.synthetic, "synthetic fragment lists added to the captured ones")->capture_default_str();
    cmd->add_option("--scenes", a.scenes, "built-in scenes to capture (builtin:NAME; default: all built-ins)");
    cmd->add_option("--capture-width", a.captureWidth, "capture resolution width")->capture_default_str();
    cmd->add_option("--capture-height", a.captureHeight, "capture resolution height")->capture_default_str();
    cmd->add_option("--families", a.families,
                    "procedural families to train on too: all or NAME,NAME (sheets, particles, foliage, shells, "
                    "strands); default none (the shipped training set), all with --hold-out");
    cmd->add_option("--family-lists", a.familyLists, "training lists per procedural family")->capture_default_str();
    cmd->add_option("--validation-lists", a.validationLists, "validation lists per procedural family")
        ->capture_default_str();
    cmd->add_option("--hold-out", a.holdOut, "train on every family but this one (a built-in scene or a procedural family)");
    cmd->add_option("--weighting", a.weighting,
                    "sample weights: none (default) or tail-visibility (starnt kinds: times ((1-a1)(1-a2))^2, "
                    "the image-space error)")
        ->capture_default_str();
    cmd->add_option("--report", a.report, "write the per-family validation errors to this JSON file");
    cmd->callback([args, cmd] {
        args->samplesGiven = cmd->get_option("--samples")->count() > 0;
        args->learningRateGiven = cmd->get_option("--learning-rate")->count() > 0;
        runTrain(*args);
    });
}

}  // namespace starnt::app
