// glcollide query tritri: answers a CSV of triangle pairs on the GPU in one batch with the
// narrow-phase test (docs/narrow-phase.md).

#include "app/commands.hpp"
#include "app/self_check_report.hpp"

#include "passes/tri_tri_query_pass.hpp"
#include "scene/tri_pair_csv.hpp"

#include <glcollide/error.hpp>
#include <glcollide/headless_context.hpp>

#include <fstream>
#include <iostream>
#include <sstream>

namespace glcollide::app {

int queryTriTriCommand(const QueryTriTriOptions& options) {
    if (options.precision != "fast" && options.precision != "robust")
        throw Error("--precision: expected fast or robust, got '" + options.precision + "'");
    const passes::TriTriPrecision precision =
        options.precision == "fast" ? passes::TriTriPrecision::Fast : passes::TriTriPrecision::Robust;
    // Parse before creating a context: a bad row fails fast and names its line.
    const TriPairCsv csv = readTriPairCsv(options.inPath);

    HeadlessContext context({options.device});
    if (precision == passes::TriTriPrecision::Robust) (void)checkRobustBeforeUse(); // docs/narrow-phase.md
    const passes::TriTriQueryPass pass(precision);
    const std::vector<passes::TriTriPair> pairs(csv.pairs.begin(), csv.pairs.end());
    const passes::TriTriQueryResult result = pass.run(pairs);

    std::ostringstream text;
    std::size_t hits = 0;
    for (std::uint8_t r : result.intersect) {
        text << (r != 0 ? "1\n" : "0\n");
        hits += r;
    }
    if (options.outPath.empty()) {
        std::cout << text.str() << std::flush;
        return 0;
    }
    std::ofstream out(options.outPath, std::ios::binary);
    if (!out) throw Error(options.outPath + ": cannot open for writing");
    out << text.str();
    out.close();
    if (!out) throw Error(options.outPath + ": write failed");
    std::cout << pairs.size() << " pairs, " << hits << " intersecting (" << passes::toString(precision)
              << " precision";
    if (precision == passes::TriTriPrecision::Robust)
        std::cout << ", " << result.undecidedPairs << " pairs to the exact pass, " << result.exactFallbacks
                  << " exact fallbacks";
    std::cout << ") on " << context.deviceDescription() << " | " << context.glInfo().renderer << "\n";
    return 0;
}

} // namespace glcollide::app
