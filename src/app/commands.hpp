// The `starnt` subcommands (docs/USAGE.md, "Command line"). Each add* function registers one subcommand on the
// CLI11 app; its callback throws starnt::Error on bad input, which main() prints as one line.
#pragma once
#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "starnt/oit_method.hpp"

namespace starnt::app {

void addRenderCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addTrainCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addViewCommand(CLI::App& app);

// The acceleration flags of the neural methods (docs/USAGE.md, "Command line") as typed; `render` and `view` declare them
// with one call so both accept the same spellings with the same help.
struct AccelerationFlags {
    std::string spatial = "default";  // on | off | default (the method's own: on for starnt)
    std::string scales = "auto";      // auto | P2,P3 in percent
    std::string inference = "full";   // full | corners
    std::string temporal = "off";     // off | auto | K in 1..8
    double targetFps = 60.0;
    std::string scaleRule = "snapped";      // snapped | continuous | step
    std::string tileSignal = "back";        // back | composite
    std::string scaleGuard = "on";          // on | off
    std::string shadingRateImage = "off";   // off | auto | on
    std::string temporalMode = "correct";   // warp | refresh | correct
    int correctedPasses = 1;                // geometry passes of a corrected frame: 1 | 2
    std::string correctedLayers = "auto";   // exact layers of a corrected frame: auto | 1 | 2
    std::string upsample = "bilinear";      // bilinear | joint
    std::string targets = "compact";        // compact | fp32
};
// "abuffer|peel|...": every name createMethod accepts, for --method's help (from the registry, so
// it cannot go stale).
std::string methodNameList();
void addAccelerationOptions(CLI::App* command, AccelerationFlags& flags);
// The acceleration flags given on this command's line (CLI11 counts), in the order of --help.
std::vector<std::string> givenAccelerationFlags(const CLI::App* command);
// Checks the flags (throws starnt::Error) and sets them on `options`.
void applyAccelerationFlags(const AccelerationFlags& flags, MethodOptions& options);

// Whether two paths name one file, however spelled ("./a.png", "a.png", "../dir/a.png"), existing or not.
bool sameFile(const std::string& a, const std::string& b);

// Parses "R,G,B" with each component finite and in [0, 1]; throws starnt::Error otherwise.
glm::vec3 parseColor(const std::string& text, const char* flag);

}  // namespace starnt::app
