#pragma once
// A small SVG plot writer for the `glcollide bench` reports: scatter and line plots with linear or
// log axes, a legend, and optionally the Pareto front (time vs error, both minimised). It has no
// plotting dependency; the output is a standalone SVG 1.1 document that browsers render as is.
//
// What is drawn and what is not:
// - A point with a non-finite coordinate (NaN, ±inf), or with a coordinate <= 0 on a log axis, is
//   skipped: nothing non-finite ever reaches the document. The skipped points are counted in a
//   footnote line under the plot ("2 points not shown: non-finite").
// - Exception: y == 0 on a log y axis. An error of exactly 0 is common (an exact method), so such
//   points are drawn on a dedicated row below the lowest decade, tick label "0", separated from the
//   decades by an axis break. They take part in the Pareto front (0 beats every positive error).
// - A data range of width zero (one point, all points equal, all y equal) is padded around the
//   value, so the axes always have a positive extent.
// - A spec without drawable points still gives a valid document: the title and a "no data" note.
// - A line (PlotSeries::connect) joins consecutive drawn points of a series in the given order; it
//   breaks at a skipped point and between the "0" row and the decades, so it never bridges a gap.
// Coordinates are written with 2 decimals, numbers with std::to_chars (independent of the locale).

#include <cstddef>
#include <string>
#include <vector>

namespace glcollide::benchkit {

// Every member has an initializer ({} included) so that brace-initialising a prefix, as in
// PlotPoint{x, y}, does not trip -Wmissing-field-initializers (part of -Wextra).
struct PlotPoint {
    double x = 0, y = 0;
    std::string label{}; ///< shown next to the point when it is on the Pareto front, or always when
                         ///< its series has labelAll; also the point's tooltip in a browser
};

struct PlotSeries {
    std::string name{};              ///< legend text
    std::vector<PlotPoint> points{}; ///< drawn in this order when `connect`
    bool connect = true;             ///< join the points with a line
    bool labelAll = false;           ///< label every point, not only those on the Pareto front
};

struct PlotSpec {
    std::string title{}, xLabel{}, yLabel{};
    bool logX = false, logY = false;
    /// Mark and label the points no other point dominates (another point is <= on both x and y
    /// and < on one; smaller is better on both), over all series, and draw the front as a dashed
    /// step line.
    bool paretoFront = false;
    std::vector<PlotSeries> series{};
    int width = 720, height = 480; ///< pixels; raised to at least 320 x 200 so the plot area fits
};

/// Indices (into `points`) of the Pareto-optimal points, minimising x and y; sorted by x (then y).
/// A point is dropped when another is <= on both coordinates and < on one. Ties: a point equal to
/// another in both coordinates keeps only the first (lowest index). Points with a non-finite
/// coordinate are never on the front. Empty input gives an empty front.
std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points);

/// A standalone SVG 1.1 document (xmlns set, viewBox, all text XML-escaped), ending with
/// "</svg>\n". See the header comment for what is drawn and what is skipped.
std::string renderSvg(const PlotSpec& spec);

/// "Nice" axis ticks, ascending, with the first tick <= lo and the last >= hi (order of lo and hi
/// does not matter). Linear: multiples of a 1/2/5 x 10^k step, 4 to 8 ticks. Log: the powers of
/// ten covering [lo, hi], plus the 2 and 5 multiples when they span fewer than 3 decades; over
/// more than 10 decades only every n-th power, so there are at most about 11 ticks. A range of
/// width zero (relative width below 1e-9) is padded first: linear by 10% of the value (±1 around
/// 0), log by half a decade each side. Empty when lo or hi is not finite, or on a log axis <= 0.
std::vector<double> axisTicks(double lo, double hi, bool log);

} // namespace glcollide::benchkit
