// The SVG plot writer (svg_plot.hpp): axis ticks, the Pareto front, and the document itself.

#include "benchkit/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

namespace glcollide::benchkit {
namespace {

// Okabe & Ito's colour-blind-safe palette, with its yellow replaced by grey (yellow is unreadable
// on white). Series beyond the eighth cycle through it again.
constexpr std::array<std::string_view, 8> kPalette = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                      "#E69F00", "#56B4E9", "#000000", "#999999"};

constexpr int kMinWidth = 320, kMinHeight = 200;
constexpr double kMarginLeft = 76, kMarginTop = 44, kMarginBottom = 56, kFootnoteHeight = 16;
constexpr double kLegendGap = 16;   // between the plot area and the legend
constexpr double kCharWidth = 7;    // rough width of a 12 px sans-serif character, to size the legend
constexpr double kZeroRowBand = 28; // log y with zeros: the "0" row sits in this band under the decades
constexpr double kPointRadius = 3.5, kFrontRingRadius = 6.5;
constexpr double kRelativeZeroWidth = 1e-9;            // a range narrower than this (relative) is one value
constexpr int kMinExponent = -323, kMaxExponent = 308; // 10^k is a positive finite double
constexpr double kMaxDouble = std::numeric_limits<double>::max();

// ---- numbers and text ----

double pow10(int k) {
    return std::pow(10.0, k);
}

// n * 10^e, rounded once: dividing by an exact power of ten gives 0.37, where multiplying by the
// inexact 0.01 gives 0.37000000000000005 (which would show on a tick label).
double scaled(double n, int e) {
    if (n == 0) return 0.0; // also turns -0 into 0, so no tick is labelled "-0"
    if (e >= 0) return n * pow10(e);
    if (e >= -300) return n / pow10(-e);
    return n * pow10(e); // 10^-e would overflow
}

// floor(log10(v)) for v > 0, exact at powers of ten (std::log10 may be one ulp off there).
int floorLog10(double v) {
    int k = static_cast<int>(std::floor(std::log10(v)));
    if (pow10(k) > v)
        --k;
    else if (pow10(k + 1) <= v)
        ++k;
    return k;
}

int ceilLog10(double v) {
    const int k = floorLog10(v);
    return pow10(k) < v ? k + 1 : k;
}

std::string toChars(double v, std::chars_format format, int precision) {
    std::array<char, 400> buf{};
    const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v, format, precision);
    if (ec != std::errc()) return "0"; // unreachable for the finite values we write
    return std::string(buf.data(), end);
}

// "1e-06" -> "1e-6", "2.5e+06" -> "2.5e6": the C exponent form is noisy on tick labels.
std::string compactExponent(const std::string& s) {
    const std::size_t e = s.find('e');
    if (e == std::string::npos) return s;
    std::string out = s.substr(0, e + 1);
    std::size_t i = e + 1;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) {
        if (s[i] == '-') out += '-';
        ++i;
    }
    while (i + 1 < s.size() && s[i] == '0') ++i;
    return out + s.substr(i);
}

// Six significant digits, compact exponent: tooltips and log tick labels.
std::string formatNumber(double v) {
    return compactExponent(toChars(v == 0 ? 0.0 : v, std::chars_format::general, 6));
}

// Log ticks are 1, 2 or 5 x 10^k: plain between 0.001 and 1000 ("0.002", "500"), else "2e-5", "1e6".
std::string formatLogTick(double v) {
    if (v >= 1e-3 && v < 1e4) return formatNumber(v);
    return compactExponent(toChars(v, std::chars_format::scientific, 0));
}

// Linear ticks: `digits` significant digits are enough to tell neighbouring ticks apart; %g-style
// formatting drops the trailing zeros ("0.4", not "0.40").
std::string formatLinearTick(double v, int digits) {
    return compactExponent(toChars(v == 0 ? 0.0 : v, std::chars_format::general, digits));
}

// Pixel coordinates: two decimals are far below what a screen shows.
std::string formatCoordinate(double v) {
    return toChars(v, std::chars_format::fixed, 2);
}

std::string escapeXml(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        case '\'':
            out += "&#39;";
            break;
        default:
            // Control characters other than tab and newlines are not allowed in XML 1.0 at all.
            if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
                out += ' ';
            else
                out += c;
        }
    }
    return out;
}

std::string attr(std::string_view name, double value) {
    return " " + std::string(name) + "=\"" + formatCoordinate(value) + "\"";
}
std::string attr(std::string_view name, std::string_view value) {
    return " " + std::string(name) + "=\"" + escapeXml(value) + "\"";
}

std::string pointCount(std::size_t n) {
    return std::to_string(n) + (n == 1 ? " point" : " points");
}

// ---- ticks ----

struct Range {
    double lo = 0, hi = 0;
};

bool isDegenerate(double lo, double hi, bool log) {
    if (log) return hi / lo < 1 + kRelativeZeroWidth;
    return hi - lo <= kRelativeZeroWidth * std::max(std::abs(lo), std::abs(hi)); // also lo == hi == 0
}

// Widens a range of (relative) width zero, so the axis has an extent to divide by.
Range padRange(double lo, double hi, bool log) {
    if (!isDegenerate(lo, hi, log)) return {lo, hi};
    if (log) {
        const double halfDecade = std::sqrt(10.0);
        return {std::max(lo / halfDecade, std::numeric_limits<double>::denorm_min()),
                std::min(hi * halfDecade, kMaxDouble)};
    }
    const double centre = lo / 2 + hi / 2;
    const double pad = centre == 0 ? 1.0 : std::abs(centre) / 10;
    return {std::max(centre - pad, -kMaxDouble), std::min(centre + pad, kMaxDouble)};
}

// The smallest 1/2/5 x 10^k step whose covering ticks number at most 8. The next smaller step is
// at most 2.5 times smaller and gives 9 or more ticks, so this one gives at least 4.
std::vector<double> linearTicks(double lo, double hi) {
    const double span = hi - lo;
    if (!std::isfinite(span)) { // |lo|, |hi| near the largest double: tick the halved range
        std::vector<double> ticks = linearTicks(lo / 2, hi / 2);
        for (double& t : ticks) t = std::clamp(t * 2, -kMaxDouble, kMaxDouble);
        return ticks;
    }
    const int firstExponent = floorLog10(span / 8) - 1;
    for (int e = firstExponent; e < firstExponent + 40; ++e) {
        for (const double m : {1.0, 2.0, 5.0}) {
            const double step = scaled(m, e);
            const double first = std::floor(lo / step), last = std::ceil(hi / step);
            if (last - first + 1 > 8) continue;
            std::vector<double> ticks;
            for (double i = first; i <= last; ++i)
                ticks.push_back(std::clamp(scaled(i * m, e), -kMaxDouble, kMaxDouble));
            return ticks;
        }
    }
    return {lo, hi}; // unreachable: a large enough step always fits
}

std::vector<double> logTicks(double lo, double hi) {
    const int kLo = std::max(floorLog10(lo), kMinExponent);
    const int kHi = std::clamp(ceilLog10(hi), kLo + 1, kMaxExponent);
    std::vector<double> ticks;
    if (kHi - kLo < 3) {
        // Few decades: 1, 2, 5 x 10^k from the last one <= lo to the first one >= hi.
        for (int k = kLo; k <= kHi; ++k) {
            for (const double m : {1.0, 2.0, 5.0}) {
                const double t = scaled(m, k);
                if (t <= lo) ticks.clear(); // a later candidate <= lo replaces the earlier ones
                if (ticks.empty() || ticks.back() < hi) ticks.push_back(t);
            }
        }
        return ticks;
    }
    // Powers of ten; over many decades every `stride`-th one, aligned to multiples of the stride.
    const int stride = (kHi - kLo + 9) / 10;
    int k = kLo >= 0 ? kLo / stride * stride : -((-kLo + stride - 1) / stride) * stride;
    if (k < kMinExponent) k += stride;
    for (;; k += stride) {
        ticks.push_back(pow10(std::min(k, kMaxExponent)));
        if (k >= kHi) break;
    }
    return ticks;
}

// ---- data ----

enum class Placement { Drawn, ZeroRow, NonFinite, NotPositive };

Placement place(const PlotPoint& p, const PlotSpec& spec) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return Placement::NonFinite;
    if ((spec.logX && p.x <= 0) || (spec.logY && p.y < 0)) return Placement::NotPositive;
    if (spec.logY && p.y == 0) return Placement::ZeroRow;
    return Placement::Drawn;
}

struct Located {
    std::size_t series = 0, index = 0;
    bool zeroRow = false;
};

struct Gathered {
    std::vector<Located> points; // drawn points, series by series
    std::size_t nonFinite = 0, notPositive = 0;
    bool zeroRow = false;
    bool hasY = false; // some drawn point is off the "0" row
    Range x{}, y{};
};

Gathered gather(const PlotSpec& spec) {
    Gathered g;
    for (std::size_t s = 0; s < spec.series.size(); ++s) {
        const std::vector<PlotPoint>& points = spec.series[s].points;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const Placement where = place(points[i], spec);
            if (where == Placement::NonFinite) {
                ++g.nonFinite;
                continue;
            }
            if (where == Placement::NotPositive) {
                ++g.notPositive;
                continue;
            }
            const PlotPoint& p = points[i];
            const bool zeroRow = where == Placement::ZeroRow;
            g.x = g.points.empty() ? Range{p.x, p.x} : Range{std::min(g.x.lo, p.x), std::max(g.x.hi, p.x)};
            if (!zeroRow) {
                g.y = g.hasY ? Range{std::min(g.y.lo, p.y), std::max(g.y.hi, p.y)} : Range{p.y, p.y};
                g.hasY = true;
            }
            g.zeroRow = g.zeroRow || zeroRow;
            g.points.push_back({s, i, zeroRow});
        }
    }
    // Only zeros on a log y axis: show the decade around 1 above the "0" row.
    if (!g.hasY) g.y = {1, 1};
    return g;
}

std::string footnote(const Gathered& g) {
    std::string text;
    if (g.nonFinite > 0) text = pointCount(g.nonFinite) + " not shown: non-finite";
    if (g.notPositive > 0) {
        if (!text.empty()) text += "; ";
        text += pointCount(g.notPositive) + " not shown: <= 0 on a log axis";
    }
    return text;
}

// ---- layout ----

struct Axis {
    bool log = false;
    std::vector<double> ticks;   // ascending; the first and last are the ends of the axis
    double pixLo = 0, pixHi = 1; // pixels of the first and last tick
    int digits = 6;              // significant digits of the linear tick labels

    double toPixel(double v) const {
        const double lo = ticks.front(), hi = ticks.back();
        // Halves on the linear axis: hi - lo may overflow near the largest double.
        const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                             : (v / 2 - lo / 2) / (hi / 2 - lo / 2);
        // Drawn points lie within the ticks by construction; the clamp keeps rounding slips (and
        // values beyond the largest tick a double can hold) inside the frame, and NaN out of it.
        return pixLo + (t >= 0 ? std::min(t, 1.0) : 0.0) * (pixHi - pixLo);
    }
    std::string label(double v) const { return log ? formatLogTick(v) : formatLinearTick(v, digits); }
};

Axis makeAxis(Range data, bool log, double pixLo, double pixHi) {
    Axis axis;
    axis.log = log;
    axis.ticks = axisTicks(data.lo, data.hi, log);
    if (axis.ticks.size() < 2) axis.ticks = log ? std::vector<double>{1, 10} : std::vector<double>{0, 1};
    axis.pixLo = pixLo;
    axis.pixHi = pixHi;
    if (!log) {
        // Enough digits to tell ticks apart: from the largest magnitude down to the step.
        const double step = axis.ticks[1] - axis.ticks[0];
        const double largest = std::max(std::abs(axis.ticks.front()), std::abs(axis.ticks.back()));
        axis.digits = std::clamp(floorLog10(largest) - floorLog10(step) + 1, 1, 17);
    }
    return axis;
}

struct Frame {
    double left = 0, top = 0, right = 0, bottom = 0; // the plot area, pixels
};

struct Layout {
    int width = 0, height = 0;
    Frame frame;
    double legendX = 0;
    double zeroRowY = 0; // pixel row of y == 0 on a log y axis (when there are such points)
    Axis x, y;
};

double legendWidth(const PlotSpec& spec, double width) {
    std::size_t longest = spec.paretoFront ? 12 : 0; // "Pareto front"
    for (const PlotSeries& s : spec.series) longest = std::max(longest, s.name.size());
    const double wanted = 2 * kLegendGap + 28 + kCharWidth * static_cast<double>(longest);
    return std::clamp(wanted, 90.0, width * 0.35);
}

Layout layOut(const PlotSpec& spec, const Gathered& g) {
    Layout l;
    l.width = std::max(spec.width, kMinWidth);
    l.height = std::max(spec.height, kMinHeight);
    const bool hasFootnote = !footnote(g).empty();
    l.frame = {kMarginLeft, kMarginTop, l.width - legendWidth(spec, l.width),
               l.height - kMarginBottom - (hasFootnote ? kFootnoteHeight : 0)};
    l.legendX = l.frame.right + kLegendGap;
    l.x = makeAxis(g.x, spec.logX, l.frame.left, l.frame.right);
    // The "0" row takes a band at the bottom; the decades start above it.
    const double yBottom = g.zeroRow ? l.frame.bottom - kZeroRowBand : l.frame.bottom;
    l.zeroRowY = l.frame.bottom - kZeroRowBand / 4;
    l.y = makeAxis(g.y, spec.logY, yBottom, l.frame.top);
    return l;
}

struct Pixel {
    double x = 0, y = 0;
};

Pixel pixelOf(const Layout& l, const PlotPoint& p, bool zeroRow) {
    return {l.x.toPixel(p.x), zeroRow ? l.zeroRowY : l.y.toPixel(p.y)};
}

std::string_view colourOf(std::size_t series) {
    return kPalette[series % kPalette.size()];
}

// ---- drawing ----

void writeHeader(std::string& out, const PlotSpec& spec, const Layout& l) {
    const std::string w = std::to_string(l.width), h = std::to_string(l.height);
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + w + "\" height=\"" + h +
           "\" viewBox=\"0 0 " + w + " " + h + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    out += "<title>" + escapeXml(spec.title) + "</title>\n";
    out += "<rect class=\"background\" x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h +
           "\" fill=\"white\"/>\n";
    if (!spec.title.empty())
        out += "<text class=\"title\"" + attr("x", l.width / 2) +
               " y=\"26\" text-anchor=\"middle\" "
               "font-size=\"16\" font-weight=\"bold\">" +
               escapeXml(spec.title) + "</text>\n";
}

void writeText(std::string& out, std::string_view cls, double x, double y, std::string_view anchor,
               std::string_view text, std::string_view extra = {}) {
    out += "<text" + attr("class", cls) + attr("x", x) + attr("y", y) + attr("text-anchor", anchor) +
           std::string(extra) + ">" + escapeXml(text) + "</text>\n";
}

void writeAxes(std::string& out, const PlotSpec& spec, const Layout& l, bool zeroRow) {
    const Frame& f = l.frame;
    out += "<g class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\">\n";
    for (const double t : l.x.ticks) {
        const double px = l.x.toPixel(t);
        out += "<line" + attr("x1", px) + attr("y1", f.top) + attr("x2", px) + attr("y2", f.bottom) + "/>\n";
    }
    for (const double t : l.y.ticks) {
        const double py = l.y.toPixel(t);
        out += "<line" + attr("x1", f.left) + attr("y1", py) + attr("x2", f.right) + attr("y2", py) + "/>\n";
    }
    if (zeroRow)
        out += "<line" + attr("x1", f.left) + attr("y1", l.zeroRowY) + attr("x2", f.right) +
               attr("y2", l.zeroRowY) + " stroke-dasharray=\"2 3\"/>\n";
    out += "</g>\n";
    out += "<rect class=\"plot-area\"" + attr("x", f.left) + attr("y", f.top) +
           attr("width", f.right - f.left) + attr("height", f.bottom - f.top) +
           " fill=\"none\" stroke=\"#333333\"/>\n";
    if (zeroRow) {
        // Axis break between the "0" row and the lowest decade: a white gap and two slashes.
        const double by = (l.zeroRowY + l.y.pixLo) / 2;
        out += "<rect class=\"axis-break\"" + attr("x", f.left - 4) + attr("y", by - 3) +
               " width=\"8\" "
               "height=\"6\" fill=\"white\"/>\n";
        out += "<path class=\"axis-break\" d=\"M" + formatCoordinate(f.left - 5) + " " +
               formatCoordinate(by) + " l10 -5 M" + formatCoordinate(f.left - 5) + " " +
               formatCoordinate(by + 5) + " l10 -5\" stroke=\"#333333\" fill=\"none\"/>\n";
    }
    out += "<g class=\"tick-labels\" fill=\"#333333\">\n";
    for (const double t : l.x.ticks)
        writeText(out, "x-tick", l.x.toPixel(t), f.bottom + 16, "middle", l.x.label(t));
    for (const double t : l.y.ticks)
        writeText(out, "y-tick", f.left - 6, l.y.toPixel(t) + 4, "end", l.y.label(t));
    if (zeroRow) writeText(out, "y-tick", f.left - 6, l.zeroRowY + 4, "end", "0");
    out += "</g>\n";
    writeText(out, "x-label", (f.left + f.right) / 2, f.bottom + 38, "middle", spec.xLabel);
    const double midY = (f.top + f.bottom) / 2;
    writeText(out, "y-label", 18, midY, "middle", spec.yLabel,
              " transform=\"rotate(-90 18 " + formatCoordinate(midY) + ")\"");
}

// The series' line: consecutive drawn points, broken at skipped points and where the line would
// cross between the "0" row and the decades.
void writeLines(std::string& out, const PlotSpec& spec, const Layout& l, std::size_t s) {
    std::string points;
    std::size_t count = 0;
    bool rowOfSegment = false;
    const auto flush = [&] {
        if (count >= 2) out += "<polyline fill=\"none\" stroke-width=\"1.5\" points=\"" + points + "\"/>\n";
        points.clear();
        count = 0;
    };
    for (const PlotPoint& p : spec.series[s].points) {
        const Placement where = place(p, spec);
        if (where == Placement::NonFinite || where == Placement::NotPositive) {
            flush();
            continue;
        }
        const bool zeroRow = where == Placement::ZeroRow;
        if (count > 0 && zeroRow != rowOfSegment) flush();
        rowOfSegment = zeroRow;
        const Pixel px = pixelOf(l, p, zeroRow);
        points += (count > 0 ? " " : "") + formatCoordinate(px.x) + "," + formatCoordinate(px.y);
        ++count;
    }
    flush();
}

void writeSeries(std::string& out, const PlotSpec& spec, const Layout& l, const Gathered& g) {
    for (std::size_t s = 0; s < spec.series.size(); ++s) {
        out += "<g class=\"series\"" + attr("fill", colourOf(s)) + attr("stroke", colourOf(s)) + ">\n";
        if (spec.series[s].connect) writeLines(out, spec, l, s);
        for (const Located& at : g.points) {
            if (at.series != s) continue;
            const PlotPoint& p = spec.series[s].points[at.index];
            const Pixel px = pixelOf(l, p, at.zeroRow);
            // The tooltip gives the exact values, which the axes only show roughly.
            std::string tip = p.label.empty() ? "" : p.label + ": ";
            tip += "(" + formatNumber(p.x) + ", " + formatNumber(p.y) + ")";
            out += "<circle class=\"point\"" + attr("cx", px.x) + attr("cy", px.y) + attr("r", kPointRadius) +
                   " stroke=\"none\"><title>" + escapeXml(tip) + "</title></circle>\n";
        }
        out += "</g>\n";
    }
}

// Indices into g.points of the points on the Pareto front, sorted by x.
std::vector<std::size_t> frontOf(const PlotSpec& spec, const Gathered& g) {
    std::vector<PlotPoint> all;
    all.reserve(g.points.size());
    for (const Located& at : g.points) {
        const PlotPoint& p = spec.series[at.series].points[at.index];
        all.push_back({p.x, p.y, {}});
    }
    return paretoFront(all);
}

// The front as a staircase: from each point right to the next one's x, then down to its y. It
// bounds the region the front dominates.
void writeFront(std::string& out, const PlotSpec& spec, const Layout& l, const Gathered& g,
                const std::vector<std::size_t>& front) {
    out += "<g class=\"pareto-front\" stroke=\"#222222\" fill=\"none\">\n";
    std::string d;
    for (const std::size_t i : front) {
        const Located& at = g.points[i];
        const Pixel px = pixelOf(l, spec.series[at.series].points[at.index], at.zeroRow);
        d += d.empty() ? "M" + formatCoordinate(px.x) + " " + formatCoordinate(px.y)
                       : " H" + formatCoordinate(px.x) + " V" + formatCoordinate(px.y);
        out += "<circle class=\"front-point\"" + attr("cx", px.x) + attr("cy", px.y) +
               attr("r", kFrontRingRadius) + " stroke-width=\"1.2\"/>\n";
    }
    if (front.size() >= 2) out += "<path d=\"" + d + "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\"/>\n";
    out += "</g>\n";
}

// Point labels last, above lines and markers; near the right edge they extend to the left.
void writeLabels(std::string& out, const PlotSpec& spec, const Layout& l, const Gathered& g,
                 const std::vector<std::size_t>& front) {
    std::vector<bool> onFront(g.points.size(), false);
    for (const std::size_t i : front) onFront[i] = true;
    out += "<g class=\"point-labels\" font-size=\"11\" fill=\"#222222\">\n";
    for (std::size_t i = 0; i < g.points.size(); ++i) {
        const Located& at = g.points[i];
        const PlotPoint& p = spec.series[at.series].points[at.index];
        if (p.label.empty() || !(onFront[i] || spec.series[at.series].labelAll)) continue;
        const Pixel px = pixelOf(l, p, at.zeroRow);
        const bool nearRight = px.x > l.frame.right - 0.25 * (l.frame.right - l.frame.left);
        writeText(out, "point-label", nearRight ? px.x - 8 : px.x + 8, px.y - 8, nearRight ? "end" : "start",
                  p.label);
    }
    out += "</g>\n";
}

void writeLegend(std::string& out, const PlotSpec& spec, const Layout& l) {
    out += "<g class=\"legend\">\n";
    double y = l.frame.top + 8;
    const double x = l.legendX;
    for (std::size_t s = 0; s < spec.series.size(); ++s, y += 18) {
        const PlotSeries& series = spec.series[s];
        out += "<g class=\"legend-entry\"" + attr("fill", colourOf(s)) + attr("stroke", colourOf(s)) + ">";
        if (series.connect)
            out += "<line" + attr("x1", x) + attr("y1", y) + attr("x2", x + 20) + attr("y2", y) +
                   " stroke-width=\"1.5\"/>";
        out +=
            "<circle" + attr("cx", x + 10) + attr("cy", y) + attr("r", kPointRadius) + " stroke=\"none\"/>";
        out += "<text" + attr("x", x + 28) + attr("y", y + 4) + " fill=\"#222222\" stroke=\"none\">" +
               escapeXml(series.name.empty() ? "series " + std::to_string(s + 1) : series.name) +
               "</text></g>\n";
    }
    if (spec.paretoFront) {
        out += "<g class=\"legend-front\" stroke=\"#222222\" fill=\"none\">";
        out += "<line" + attr("x1", x) + attr("y1", y) + attr("x2", x + 20) + attr("y2", y) +
               " stroke-width=\"1.2\" stroke-dasharray=\"6 4\"/>";
        out += "<circle" + attr("cx", x + 10) + attr("cy", y) + attr("r", kFrontRingRadius) + "/>";
        out += "<text" + attr("x", x + 28) + attr("y", y + 4) +
               " fill=\"#222222\" stroke=\"none\">"
               "Pareto front</text></g>\n";
    }
    out += "</g>\n";
}

void writeFootnote(std::string& out, const Layout& l, const Gathered& g) {
    const std::string text = footnote(g);
    if (!text.empty())
        writeText(out, "footnote", kMarginLeft, l.height - 8, "start", text,
                  " font-size=\"11\" fill=\"#555555\"");
}

} // namespace

std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (std::isfinite(points[i].x) && std::isfinite(points[i].y)) order.push_back(i);
    // Stable: of equal points the first stays first, and the sweep keeps only it.
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::pair(points[a].x, points[a].y) < std::pair(points[b].x, points[b].y);
    });
    // In x order, a point is on the front iff its y beats every y before it: those have a smaller
    // or equal x, so one with y <= this y would dominate it.
    std::vector<std::size_t> front;
    double bestY = std::numeric_limits<double>::infinity();
    for (const std::size_t i : order) {
        if (points[i].y < bestY) {
            front.push_back(i);
            bestY = points[i].y;
        }
    }
    return front;
}

std::vector<double> axisTicks(double lo, double hi, bool log) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (lo > hi) std::swap(lo, hi);
    if (log && lo <= 0) return {};
    const Range r = padRange(lo, hi, log);
    return log ? logTicks(r.lo, r.hi) : linearTicks(r.lo, r.hi);
}

std::string renderSvg(const PlotSpec& spec) {
    const Gathered g = gather(spec);
    const Layout l = layOut(spec, g);
    std::string out;
    writeHeader(out, spec, l);
    if (g.points.empty()) {
        writeText(out, "note", l.width / 2, l.height / 2, "middle", "no data", " fill=\"#555555\"");
    } else {
        const std::vector<std::size_t> front =
            spec.paretoFront ? frontOf(spec, g) : std::vector<std::size_t>{};
        writeAxes(out, spec, l, g.zeroRow);
        writeSeries(out, spec, l, g);
        if (spec.paretoFront) writeFront(out, spec, l, g, front);
        writeLabels(out, spec, l, g, front);
        writeLegend(out, spec, l);
    }
    writeFootnote(out, l, g);
    out += "</svg>\n";
    return out;
}

} // namespace glcollide::benchkit
