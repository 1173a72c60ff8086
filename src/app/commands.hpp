// The `starnt` subcommands (SPEC section 9). Each add* function registers one subcommand on the
// CLI11 app; its callback throws starnt::Error on bad input, which main() prints as one line.
#pragma once
#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

namespace starnt::app {

void addRenderCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addTrainCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addViewCommand(CLI::App& app);

// Parses "R,G,B" with each component finite and in [0, 1]; throws starnt::Error otherwise.
glm::vec3 parseColor(const std::string& text, const char* flag);

}  // namespace starnt::app
