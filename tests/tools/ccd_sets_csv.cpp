// Writes the Scalable-CCD query sets (cloth-funnel 227 -> 228 and cloth-ball 92 -> 93, rebuilt from
// their frames by src/cpu/oracle/ccd_query_sets.cpp) as CSV files in the Sample-Queries layout:
// 8 rows per query, each row x, y, z as numerator,denominator pairs (exact), then the upstream
// exact answer (mma_bool) as a 7th column. Peers that read the CCD benchmark's CSVs (the
// Tight-Inclusion driver in bench/peers/tight-inclusion/) then read these sets the same way.
//
//   glcollide_ccd_sets_csv EXTERNAL_DIR OUT_DIR
//     EXTERNAL_DIR: tests/data/external; OUT_DIR: created if missing. Writes cloth-funnel-vf.csv,
//     cloth-funnel-ee.csv, cloth-ball-vf.csv and cloth-ball-ee.csv there (the listed pairs), and
//     cloth-funnel-candidates-vf.csv and cloth-funnel-candidates-ee.csv (every swept-box candidate
//     of the funnel step, 7,319 and 33,770; truth 1 for the listed colliding pairs and 0 for the
//     rest, which the data's README found collision-free by a numerical check, not an exact one),
//     and names each on stdout.

#include "cpu/oracle/ccd_query_sets.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

namespace {

/// Every swept-box candidate of the set's step, true when it is a listed colliding pair.
void writeCandidates(const glcollide::cpu::ScalableCcdSet& set, const std::filesystem::path& path) {
    using namespace glcollide::cpu;
    const CcdStep step = readCcdStep(set.startFrame, set.endFrame);
    const std::vector<BoxPair> listed = readBoxPairs(set.boxes);
    const std::vector<bool> truth = readMmaBool(set.truth);
    std::vector<BoxPair> colliding;
    for (std::size_t i = 0; i < listed.size() && i < truth.size(); ++i)
        if (truth[i]) colliding.push_back(listed[i]);
    std::sort(colliding.begin(), colliding.end());
    std::vector<SampleCcdQuery> queries;
    for (const BoxPair& pair : sweptBoxCandidates(step, set.kind))
        queries.push_back({rationalQuery(ccdPairPoints(step, set.kind, pair)),
                           std::binary_search(colliding.begin(), colliding.end(), pair)});
    writeSampleCcdQueries(path.string(), queries);
    std::printf("%s: %zu queries\n", path.string().c_str(), queries.size());
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s EXTERNAL_DIR OUT_DIR\n", argv[0]);
        return 2;
    }
    try {
        const std::filesystem::path out = argv[2];
        std::filesystem::create_directories(out);
        for (const glcollide::cpu::ScalableCcdSet& set : glcollide::cpu::scalableCcdSets(argv[1])) {
            std::string file = set.name; // "cloth-ball vf" -> "cloth-ball-vf.csv"
            file[file.find(' ')] = '-';
            const std::filesystem::path path = out / (file + ".csv");
            const auto queries = glcollide::cpu::readScalableCcdQueries(set);
            glcollide::cpu::writeSampleCcdQueries(path.string(), queries);
            std::printf("%s: %zu queries\n", path.string().c_str(), queries.size());
            if (file.starts_with("cloth-funnel"))
                writeCandidates(set, out / ("cloth-funnel-candidates-" + file.substr(13) + ".csv"));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glcollide_ccd_sets_csv: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
