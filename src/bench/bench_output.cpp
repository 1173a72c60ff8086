#include "bench/bench_output.hpp"

#include <filesystem>

#include "bench/bench_report.hpp"
#include "bench/plots.hpp"
#include "starnt/tools/image.hpp"

namespace starnt::bench {

void writeBenchOutputs(Results& results, const std::string& outDir, const std::string& python) {
    namespace fs = std::filesystem;
    const std::string json = (fs::path(outDir) / "results.json").string();
    results.plots = {};
    results.plots.reason = python.empty() ? "plots turned off (--no-plots)" : "not drawn yet";
    writeFileAtomic(json, toJson(results).dump(2) + "\n");
    writeFileAtomic((fs::path(outDir) / "results.csv").string(), toCsv(results));
    if (!python.empty()) {
        results.plots = makePlots(outDir, python);
        writeFileAtomic(json, toJson(results).dump(2) + "\n");  // now with the plot status
    }
    writeFileAtomic((fs::path(outDir) / "report.md").string(), reportMarkdown(results));
}

}  // namespace starnt::bench
