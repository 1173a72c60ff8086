// starnt: render, compare, train and benchmark OIT methods (docs/USAGE.md, "Command line").
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#ifdef __GLIBC__  // defined by the C library's headers above
#include <malloc.h>
#endif

#include "app/commands.hpp"
#include "starnt/error.hpp"
#include "starnt/log.hpp"
#include "starnt/oit_method.hpp"
#include "starnt/tools/scene.hpp"

int main(int argc, char** argv) {
#ifdef __GLIBC__
    // Keep freed heap memory in the process: glibc returns the top of the heap to the system once
    // 128 KiB of it is free, and llvmpipe frees and reallocates its per-scene memory many times a
    // frame, so every frame faulted tens of MB back in (docs/DESIGN.md, "Findings on Mesa
    // llvmpipe": chess at 720p, DFAOIT 128 -> 52 ms a frame). Process-wide, so the tool sets it and
    // the libraries do not (docs/INTEGRATION.md).
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
    // The libraries never write to stderr themselves: their notes and warnings come here.
    starnt::setLogCallback([](starnt::LogLevel level, const std::string& message) {
        std::fprintf(stderr, "starnt: %s: %s\n", level == starnt::LogLevel::Warning ? "warning" : "note", message.c_str());
    });
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
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
            known = known || sub->check_name(argv[1]);
        if (!known) {
            std::fprintf(stderr, "starnt: error: unknown command '%s' (expected render, compare, train, bench, view, "
                                 "methods or scenes; see starnt --help)\n", argv[1]);
            return 1;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);  // --help (and the like): usage on stdout, exit 0
    } catch (const CLI::ParseError& e) {
        // Usage errors: one line like every other error (docs/USAGE.md, "Command line"), pointing at --help.
        std::string message = e.what();
        for (char& c : message)
            if (c == '\n' || c == '\r') c = ' ';
        while (!message.empty() && message.back() == ' ') message.pop_back();
        std::fprintf(stderr, "starnt: error: %s (see starnt --help)\n", message.c_str());
        return e.get_exit_code() != 0 ? e.get_exit_code() : 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "starnt: error: out of memory\n");
        return 1;
    } catch (const starnt::Error& e) {
        std::fprintf(stderr, "starnt: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "starnt: internal error: %s\n", e.what());
        return 2;
    }
    return 0;
}
