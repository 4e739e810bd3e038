#pragma once
// Capped CCD queries continue on halves of their time interval (docs/ccd.md, "query ccd"): a query
// whose search ran out of budget is re-posed as two queries, over [0, 1/2] and [1/2, 1] of its
// interval, each with a budget of its own, for a given number of rounds. GL-free: CcdQueryPass
// runs it with the GPU kernel, the tests with the C++ twin, so both continue the same way.
//
// Linear motion restricted to a sub-interval is linear motion, so each piece is again a CCD query
// on [0, 1]; only the positions at the split time are new, and they are rounded to float. The
// rounding is covered as for the input (cpu/oracle/ccd_rounding.hpp): the piece's minimum
// separation grows by twice the largest rounding error of those positions (an upper bound,
// computed exactly in double arithmetic), because each coordinate of F combines each primitive's
// points with weights that sum to 1 (docs/ccd.md, "query ccd: rounded inputs").

#include "passes/ccd_query_pass.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace glcollide::passes {

/// Answers a batch of queries, one answer per query in order.
using CcdSolver = std::function<std::vector<CcdAnswer>(const std::vector<CcdQuery>&)>;

/// The query over half of its time interval (half 0: [0, 1/2], half 1: [1/2, 1]) as a query on
/// [0, 1]: the positions at t = 1/2 rounded to float, the minimum separation widened to cover that
/// rounding (and kept normal after the CCD's normalization, core/ccd_cover.hpp). std::nullopt when
/// the widened separation does not fit in a float.
std::optional<CcdQuery> halfOfTime(const CcdQuery& query, int half);

/// Answers `queries` with `solve`, then runs up to `rounds` more rounds in which every capped
/// piece that can still change its query's answer (none of its query's earlier pieces may collide
/// without being capped) is replaced by its two halves. A query may collide when one of its pieces
/// may; its time of impact is that of its earliest such piece mapped back to [0, 1] (rounded down
/// to a float); it is capped when only capped pieces make it "may collide".
CcdQueryResult answerWithContinuation(const std::vector<CcdQuery>& queries, const CcdSolver& solve,
                                      int rounds);

} // namespace glcollide::passes
