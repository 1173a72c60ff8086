// starnt: render, compare, train and benchmark OIT methods (SPEC section 9).
#include <cstdio>
#include <exception>

#include "app/commands.hpp"
#include "starnt/error.hpp"
#include "starnt/oit_method.hpp"
#include "starnt/scene.hpp"

int main(int argc, char** argv) {
    CLI::App app{"STAR-NT: neural order-independent transparency with spatial and temporal acceleration"};
    app.require_subcommand(1);
    starnt::app::addRenderCommand(app);
    starnt::app::addCompareCommand(app);
    starnt::app::addTrainCommand(app);
    starnt::app::addBenchCommand(app);
    starnt::app::addViewCommand(app);
    app.add_subcommand("methods", "list the OIT methods, one per line")->callback([] {
        for (const auto& m : starnt::methodNames()) std::printf("%s\n", m.c_str());
    });
    app.add_subcommand("scenes", "list the built-in scenes (use as --scene builtin:NAME)")->callback([] {
        for (const auto& s : starnt::builtinSceneNames()) std::printf("builtin:%s\n", s.c_str());
    });
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);  // usage errors: message on stderr, non-zero exit (0 for --help)
    } catch (const starnt::Error& e) {
        std::fprintf(stderr, "starnt: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "starnt: internal error: %s\n", e.what());
        return 2;
    }
    return 0;
}
