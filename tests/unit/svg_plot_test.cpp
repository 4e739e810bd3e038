// SVG plot writer (src/benchkit/svg_plot.cpp): the Pareto front, axis ticks, and the documents
// renderSvg writes for ordinary and hard inputs (non-finite values, zeros and negatives on log
// axes, ranges of width zero, no data, markup in text). The documents are checked with a small
// well-formedness checker that is enough for our own output.
//
// Set GLCOLLIDE_SVG_SAMPLE=/path/file.svg to also write a sample plot there (for a look in a
// browser, or xmllint).

#include "benchkit/svg_plot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace glcollide::benchkit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- helpers over the documents ----

// Empty when `doc` is well-formed as far as our output goes: one root element, every `<name ...>`
// closed by `</name>` in order (or self-closing `/>`), quotes paired inside tags, and every `&`
// starting an entity. Otherwise what is wrong.
std::string wellFormedError(const std::string& doc) {
    std::vector<std::string> open;
    std::size_t pos = 0, roots = 0;
    while ((pos = doc.find('<', pos)) != std::string::npos) {
        const std::size_t end = doc.find('>', pos);
        if (end == std::string::npos) return "unterminated tag at " + std::to_string(pos);
        const std::string tag = doc.substr(pos + 1, end - pos - 1);
        if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return "unpaired quote in <" + tag + ">";
        if (tag.empty() || tag.find('<') != std::string::npos) return "bad tag at " + std::to_string(pos);
        if (tag[0] == '/') {
            if (open.empty() || open.back() != tag.substr(1)) return "unbalanced </" + tag.substr(1) + ">";
            open.pop_back();
        } else {
            if (open.empty() && ++roots > 1) return "second root element <" + tag + ">";
            if (tag.back() != '/') open.push_back(tag.substr(0, tag.find_first_of(" \n/")));
        }
        pos = end + 1;
    }
    if (!open.empty()) return "unclosed <" + open.back() + ">";
    static const std::vector<std::string> entities = {"&amp;", "&lt;", "&gt;", "&quot;", "&#39;"};
    for (std::size_t amp = doc.find('&'); amp != std::string::npos; amp = doc.find('&', amp + 1)) {
        const bool ok = std::any_of(entities.begin(), entities.end(),
                                    [&](const std::string& e) { return doc.compare(amp, e.size(), e) == 0; });
        if (!ok) return "bare & at " + std::to_string(amp);
    }
    if (doc.find('>', doc.rfind('<')) == std::string::npos) return "text after the last tag";
    return {};
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::size_t countOf(const std::string& doc, const std::string& needle) {
    std::size_t n = 0;
    for (std::size_t p = doc.find(needle); p != std::string::npos; p = doc.find(needle, p + 1)) ++n;
    return n;
}

struct Circle {
    double cx = 0, cy = 0;
};

// The data markers (class "point"), in document order.
std::vector<Circle> pointCircles(const std::string& doc) {
    static const std::regex re(R"re(<circle class="point" cx="([^"]*)" cy="([^"]*)")re");
    std::vector<Circle> circles;
    for (auto it = std::sregex_iterator(doc.begin(), doc.end(), re); it != std::sregex_iterator(); ++it)
        circles.push_back({std::stod((*it)[1]), std::stod((*it)[2])});
    return circles;
}

struct Area {
    double left = 0, top = 0, right = 0, bottom = 0;
};

Area plotArea(const std::string& doc) {
    static const std::regex re(
        R"re(<rect class="plot-area" x="([^"]*)" y="([^"]*)" width="([^"]*)" height="([^"]*)")re");
    std::smatch m;
    if (!std::regex_search(doc, m, re)) {
        ADD_FAILURE() << "no plot area";
        return {};
    }
    const double x = std::stod(m[1]), y = std::stod(m[2]);
    return {x, y, x + std::stod(m[3]), y + std::stod(m[4])};
}

// Every numeric attribute value parses completely to a finite number.
void expectFiniteNumbers(const std::string& doc) {
    static const std::regex re(R"re( (x|y|x1|y1|x2|y2|cx|cy|r|width|height)="([^"]*)")re");
    for (auto it = std::sregex_iterator(doc.begin(), doc.end(), re); it != std::sregex_iterator(); ++it) {
        const std::string value = (*it)[2];
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        EXPECT_TRUE(end == value.c_str() + value.size() && std::isfinite(v)) << (*it)[0];
    }
}

// The checks every document must pass, whatever went in.
void expectValidDocument(const std::string& doc) {
    ASSERT_EQ(doc.rfind("<svg", 0), 0u) << doc.substr(0, 40);
    ASSERT_GE(doc.size(), 7u);
    EXPECT_EQ(doc.substr(doc.size() - 7), "</svg>\n");
    EXPECT_NE(doc.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
    EXPECT_NE(doc.find("viewBox=\"0 0 "), std::string::npos);
    EXPECT_EQ(wellFormedError(doc), "");
    const std::string l = lower(doc);
    EXPECT_EQ(l.find("nan"), std::string::npos);
    EXPECT_EQ(l.find("inf"), std::string::npos);
    expectFiniteNumbers(doc);
}

void expectPointsInside(const std::string& doc, std::size_t expectedCount) {
    const std::vector<Circle> circles = pointCircles(doc);
    EXPECT_EQ(circles.size(), expectedCount);
    if (circles.empty()) return; // "no data": no plot area either
    const Area a = plotArea(doc);
    for (const Circle& c : circles) {
        EXPECT_GE(c.cx, a.left);
        EXPECT_LE(c.cx, a.right);
        EXPECT_GE(c.cy, a.top);
        EXPECT_LE(c.cy, a.bottom);
    }
}

PlotSeries seriesOf(std::string name, std::vector<PlotPoint> points) {
    PlotSeries s;
    s.name = std::move(name);
    s.points = std::move(points);
    return s;
}

// A time-vs-error plot like `glcollide bench` draws: three methods, one exact (error 0).
PlotSpec timeErrorSpec() {
    PlotSpec spec;
    spec.title = "Contact time vs error";
    spec.xLabel = "time per step (ms)";
    spec.yLabel = "max position error (m)";
    spec.logX = spec.logY = true;
    spec.paretoFront = true;
    spec.series.push_back(
        seriesOf("float", {{0.8, 3e-4, "f32 d=1"}, {1.5, 8e-5, "f32 d=2"}, {3.2, 7e-5, "f32 d=3"}}));
    spec.series.push_back(
        seriesOf("double", {{2.0, 2e-6, "f64 d=1"}, {4.1, 9e-7, "f64 d=2"}, {2.5, 5e-4, "slow"}}));
    spec.series.push_back(seriesOf("exact", {{25.0, 0.0, "exact"}}));
    return spec;
}

// ---- paretoFront ----

TEST(SvgPlotParetoFront, KeepsUndominatedPointsSortedByX) {
    const std::vector<PlotPoint> points = {
        {3, 1, "c"},  {1, 5, "a"}, {2, 6, "dominated by a"}, {2, 2, "b"}, {4, 1, "dominated by c"},
        {5, 0.5, "d"}};
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{1, 3, 0, 5}));
}

TEST(SvgPlotParetoFront, EqualXOrEqualYIsDominatedByTheBetterOther) {
    // Same x, larger y; same y, larger x: both dominated (<= on both, < on one).
    const std::vector<PlotPoint> points = {{1, 4}, {1, 3}, {2, 3}, {0.5, 9}};
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{3, 1}));
}

TEST(SvgPlotParetoFront, EqualPointsKeepOnlyTheFirst) {
    const std::vector<PlotPoint> points = {
        {2, 2, "later"}, {1, 3, "first"}, {1, 3, "second"}, {1, 3, "third"}};
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{1, 0}));
}

TEST(SvgPlotParetoFront, SinglePointAndEmpty) {
    EXPECT_EQ(paretoFront({{7, 8}}), (std::vector<std::size_t>{0}));
    EXPECT_TRUE(paretoFront({}).empty());
}

TEST(SvgPlotParetoFront, NonFiniteNeverOnFront) {
    const std::vector<PlotPoint> points = {{kNaN, 0}, {1, 1}, {-kInf, 5}, {0, kNaN}, {2, 0.5}};
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{1, 4}));
}

TEST(SvgPlotParetoFront, ZeroErrorBeatsEveryPositiveError) {
    const std::vector<PlotPoint> points = {{1, 1e-3}, {10, 0}, {20, 0}};
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{0, 1}));
}

// ---- axisTicks ----

void expectCovering(const std::vector<double>& ticks, double lo, double hi) {
    ASSERT_GE(ticks.size(), 2u);
    EXPECT_LE(ticks.front(), lo);
    EXPECT_GE(ticks.back(), hi);
    EXPECT_TRUE(std::is_sorted(ticks.begin(), ticks.end()));
    EXPECT_EQ(std::adjacent_find(ticks.begin(), ticks.end()), ticks.end()) << "repeated tick";
    for (const double t : ticks) EXPECT_TRUE(std::isfinite(t));
}

TEST(SvgPlotAxisTicks, LinearZeroToOne) {
    EXPECT_EQ(axisTicks(0, 1, false), (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1}));
}

TEST(SvgPlotAxisTicks, LinearNarrowRangeHasExactDecimals) {
    // Exactly the doubles nearest 0.37 .. 0.41, not 0.37000000000000005 (would show in labels).
    EXPECT_EQ(axisTicks(0.37, 0.41, false), (std::vector<double>{0.37, 0.38, 0.39, 0.4, 0.41}));
    EXPECT_EQ(axisTicks(0.41, 0.37, false), axisTicks(0.37, 0.41, false)); // order does not matter
}

TEST(SvgPlotAxisTicks, LinearHasFourToEightNiceTicks) {
    const std::vector<std::pair<double, double>> ranges = {
        {0, 1},         {0.37, 0.41}, {-3, 7},       {-1e-9, 2e-9},   {123, 4567},         {1, 1.001},
        {-50, -49},     {0, 9.9},     {0.001, 1000}, {-1e300, 1e300}, {-1.7e308, 1.7e308}, {1e-300, 3e-300},
        {1e15, 1.01e15}};
    for (const auto& [lo, hi] : ranges) {
        SCOPED_TRACE(std::to_string(lo) + " .. " + std::to_string(hi));
        const std::vector<double> ticks = axisTicks(lo, hi, false);
        expectCovering(ticks, lo, hi);
        EXPECT_GE(ticks.size(), 4u);
        EXPECT_LE(ticks.size(), 8u);
        // Evenly spaced by a 1, 2 or 5 x 10^k step (measured in the middle: the end ticks of
        // +-1.7e308 are clamped to the largest double).
        const double step = ticks[ticks.size() / 2] - ticks[ticks.size() / 2 - 1];
        const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
        EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                    std::abs(mantissa - 5) < 1e-6)
            << step;
    }
}

TEST(SvgPlotAxisTicks, LogPowersOfTen) {
    EXPECT_EQ(axisTicks(1e-3, 1e2, true), (std::vector<double>{1e-3, 1e-2, 1e-1, 1, 10, 100}));
    const std::vector<double> ten = axisTicks(3e-5, 2e4, true); // 10 decades: every power
    expectCovering(ten, 3e-5, 2e4);
    EXPECT_EQ(ten.size(), 11u);
    EXPECT_EQ(ten.front(), 1e-5);
    EXPECT_EQ(ten.back(), 1e5);
}

TEST(SvgPlotAxisTicks, LogWithinOneDecadeAddsTwoAndFive) {
    EXPECT_EQ(axisTicks(0.3, 0.8, true), (std::vector<double>{0.2, 0.5, 1}));
    EXPECT_EQ(axisTicks(1, 10, true), (std::vector<double>{1, 2, 5, 10}));
    EXPECT_EQ(axisTicks(0.015, 0.9, true), (std::vector<double>{0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1}));
}

TEST(SvgPlotAxisTicks, LogOverManyDecadesStaysShort) {
    // 14 decades: every second power, aligned to even exponents.
    EXPECT_EQ(axisTicks(3e-7, 2e5, true), (std::vector<double>{1e-8, 1e-6, 1e-4, 1e-2, 1, 1e2, 1e4, 1e6}));
    const std::vector<double> ticks = axisTicks(1e-300, 1e300, true);
    expectCovering(ticks, 1e-300, 1e300);
    EXPECT_LE(ticks.size(), 12u);
}

TEST(SvgPlotAxisTicks, RangeOfWidthZeroIsPadded) {
    for (const double v : {5.0, 0.0, -2.5, 1e-12}) {
        SCOPED_TRACE(v);
        const std::vector<double> ticks = axisTicks(v, v, false);
        expectCovering(ticks, v, v);
        EXPECT_GE(ticks.size(), 4u);
    }
    const std::vector<double> logTicks = axisTicks(10, 10, true);
    expectCovering(logTicks, 10, 10);
    EXPECT_LT(logTicks.front(), 10);
    EXPECT_GT(logTicks.back(), 10);
}

TEST(SvgPlotAxisTicks, InvalidRangesGiveNoTicks) {
    EXPECT_TRUE(axisTicks(kNaN, 1, false).empty());
    EXPECT_TRUE(axisTicks(0, kInf, false).empty());
    EXPECT_TRUE(axisTicks(0, 1, true).empty());
    EXPECT_TRUE(axisTicks(-1, 1, true).empty());
}

// ---- renderSvg ----

TEST(SvgPlotRender, TimeErrorPlotIsValidWithFrontAndLegend) {
    const PlotSpec spec = timeErrorSpec();
    const std::string doc = renderSvg(spec);
    expectValidDocument(doc);
    expectPointsInside(doc, 7);
    EXPECT_EQ(countOf(doc, "class=\"legend-entry\""), spec.series.size());
    EXPECT_EQ(countOf(doc, "class=\"legend-front\""), 1u);
    EXPECT_NE(doc.find(">Contact time vs error</text>"), std::string::npos);
    EXPECT_NE(doc.find(">time per step (ms)</text>"), std::string::npos);
    EXPECT_NE(doc.find(">max position error (m)</text>"), std::string::npos);

    // Front over all series: f32 d=1 (0.8 ms), f32 d=2, f64 d=1, f64 d=2, exact (error 0); f32 d=3
    // is beaten by f64 d=1 (faster and more accurate), slow by f64 d=1 too.
    EXPECT_EQ(countOf(doc, "class=\"front-point\""), 5u);
    for (const char* label : {">f32 d=1<", ">f32 d=2<", ">f64 d=1<", ">f64 d=2<", ">exact<"})
        EXPECT_NE(doc.find(label), std::string::npos) << label;
    for (const char* label : {">f32 d=3<", ">slow<"}) EXPECT_EQ(doc.find(label), std::string::npos) << label;
    const std::size_t front = doc.find("<g class=\"pareto-front\"");
    ASSERT_NE(front, std::string::npos);
    const std::size_t path = doc.find("<path d=\"M", front);
    ASSERT_NE(path, std::string::npos);
    EXPECT_NE(doc.substr(path, doc.find("/>", path) - path).find("stroke-dasharray"), std::string::npos);

    if (const char* sample = std::getenv("GLCOLLIDE_SVG_SAMPLE")) std::ofstream(sample) << doc;
}

TEST(SvgPlotRender, ZeroOnLogYGetsItsOwnRowBelowTheDecades) {
    const std::string doc = renderSvg(timeErrorSpec());
    EXPECT_NE(doc.find("class=\"y-tick\""), std::string::npos);
    EXPECT_NE(doc.find(">0</text>"), std::string::npos);
    EXPECT_NE(doc.find("class=\"axis-break\""), std::string::npos);
    const std::vector<Circle> circles = pointCircles(doc);
    ASSERT_EQ(circles.size(), 7u);
    const double zeroRowY = circles.back().cy; // the exact method's point comes last
    for (std::size_t i = 0; i + 1 < circles.size(); ++i) EXPECT_LT(circles[i].cy, zeroRowY - 10);
    EXPECT_EQ(doc.find("not shown"), std::string::npos); // a zero error is drawn, not skipped
}

TEST(SvgPlotRender, NonFiniteAndNonPositiveOnLogAreSkippedWithAFootnote) {
    PlotSpec spec;
    spec.title = "skips";
    spec.logX = spec.logY = true;
    spec.series.push_back(
        seriesOf("a", {{1, 1}, {kNaN, 2}, {2, kInf}, {3, 0.5}, {-1, 1}, {0, 2}, {4, -1e-3}}));
    const std::string doc = renderSvg(spec);
    expectValidDocument(doc);
    expectPointsInside(doc, 2);
    EXPECT_NE(doc.find("2 points not shown: non-finite; 3 points not shown: &lt;= 0 on a log axis"),
              std::string::npos);
    // The line breaks at skipped points: {1,1} and {3,0.5} are not neighbours in the series.
    EXPECT_EQ(doc.find("<polyline"), std::string::npos);
}

TEST(SvgPlotRender, OneSkippedPointIsSingular) {
    PlotSpec spec;
    spec.series.push_back(seriesOf("a", {{1, 1}, {2, -kInf}, {3, 2}}));
    const std::string doc = renderSvg(spec);
    expectValidDocument(doc);
    EXPECT_NE(doc.find("1 point not shown: non-finite"), std::string::npos);
    expectPointsInside(doc, 2);
}

TEST(SvgPlotRender, RangesOfWidthZero) {
    const std::vector<std::vector<PlotPoint>> cases = {
        {{3, 4}},                 // single point
        {{2, 2}, {2, 2}, {2, 2}}, // all equal
        {{1, 5}, {2, 5}, {3, 5}}, // all y equal
        {{7, 1}, {7, 2}},         // all x equal
        {{0, 0}},                 // at the origin
    };
    for (const bool log : {false, true}) {
        for (const std::vector<PlotPoint>& points : cases) {
            SCOPED_TRACE(std::to_string(points.size()) + " points, log " + std::to_string(log));
            PlotSpec spec;
            spec.logX = spec.logY = log;
            spec.paretoFront = true;
            spec.series.push_back(seriesOf("s", points));
            const std::string doc = renderSvg(spec);
            expectValidDocument(doc);
            const bool origin = points[0].x == 0;
            expectPointsInside(doc, log && origin ? 0 : points.size()); // x = 0 is skipped on log x
        }
    }
}

TEST(SvgPlotRender, EmptySpecIsAValidDocumentSayingNoData) {
    PlotSpec spec;
    spec.title = "nothing yet";
    for (int variant = 0; variant < 3; ++variant) {
        if (variant == 1) spec.series.push_back(seriesOf("empty", {}));
        if (variant == 2) spec.series.push_back(seriesOf("all bad", {{kNaN, 1}, {1, kNaN}}));
        SCOPED_TRACE(variant);
        const std::string doc = renderSvg(spec);
        expectValidDocument(doc);
        EXPECT_NE(doc.find(">nothing yet</text>"), std::string::npos);
        EXPECT_NE(doc.find(">no data</text>"), std::string::npos);
        EXPECT_EQ(pointCircles(doc).size(), 0u);
        EXPECT_EQ(doc.find("not shown") != std::string::npos, variant == 2);
    }
    expectValidDocument(renderSvg(PlotSpec{}));
}

TEST(SvgPlotRender, TextIsEscaped) {
    PlotSpec spec;
    spec.title = "a < b & \"c\" > d";
    spec.xLabel = "<x>";
    spec.yLabel = "y's";
    spec.paretoFront = true;
    spec.series.push_back(seriesOf("</g><script>", {{1, 2, "<b>&"}}));
    const std::string doc = renderSvg(spec);
    expectValidDocument(doc);
    EXPECT_NE(doc.find("a &lt; b &amp; &quot;c&quot; &gt; d"), std::string::npos);
    EXPECT_EQ(doc.find("a < b"), std::string::npos);
    EXPECT_NE(doc.find("&lt;x&gt;"), std::string::npos);
    EXPECT_NE(doc.find("&lt;/g&gt;&lt;script&gt;"), std::string::npos);
    EXPECT_NE(doc.find(">&lt;b&gt;&amp;</text>"), std::string::npos); // the front point's label
    EXPECT_EQ(doc.find("<script"), std::string::npos);
}

TEST(SvgPlotRender, SeriesGetDistinctColoursThenCycle) {
    PlotSpec spec;
    for (int s = 0; s < 9; ++s)
        spec.series.push_back(seriesOf("s" + std::to_string(s), {{double(s), 1.0 + s}}));
    const std::string doc = renderSvg(spec);
    expectValidDocument(doc);
    EXPECT_EQ(countOf(doc, "class=\"legend-entry\""), 9u);
    static const std::regex re(R"re(<g class="series" fill="([^"]*)")re");
    std::vector<std::string> colours;
    for (auto it = std::sregex_iterator(doc.begin(), doc.end(), re); it != std::sregex_iterator(); ++it)
        colours.push_back((*it)[1]);
    ASSERT_EQ(colours.size(), 9u);
    EXPECT_EQ(std::set<std::string>(colours.begin(), colours.begin() + 8).size(), 8u);
    EXPECT_EQ(colours[8], colours[0]);
}

TEST(SvgPlotRender, TickLabelsAreCompact) {
    PlotSpec spec;
    spec.logX = spec.logY = true;
    spec.series.push_back(seriesOf("mesh", {{1e-6, 1e-3}, {1e6, 2.5}}));
    const std::string doc = renderSvg(spec);
    expectValidDocument(doc);
    for (const char* label : {">1e-6</text>", ">1e6</text>", ">0.01</text>", ">1</text>", ">100</text>"})
        EXPECT_NE(doc.find(label), std::string::npos) << label;
    EXPECT_EQ(doc.find("e-06"), std::string::npos);
    EXPECT_EQ(doc.find("e+"), std::string::npos);

    PlotSpec linear;
    linear.series.push_back(seriesOf("narrow", {{0.37, 1000}, {0.41, 1001}}));
    const std::string lin = renderSvg(linear);
    for (const char* label : {">0.37</text>", ">0.4</text>", ">1000</text>", ">1000.2</text>"})
        EXPECT_NE(lin.find(label), std::string::npos) << label;
}

TEST(SvgPlotRender, LineSeriesAndLabelAll) {
    PlotSpec spec;
    spec.title = "time vs mesh size";
    spec.logX = spec.logY = true;
    PlotSeries s = seriesOf("octree", {{100, 0.1, "100"}, {1000, 0.5, "1k"}, {10000, 4, "10k"}});
    s.labelAll = true;
    PlotSeries dots = seriesOf("dots", {{200, 0.2}, {2000, 0.9}});
    dots.connect = false;
    spec.series = {s, dots};
    const std::string doc = renderSvg(spec);
    expectValidDocument(doc);
    expectPointsInside(doc, 5);
    EXPECT_EQ(countOf(doc, "<polyline"), 1u);
    for (const char* label : {">100<", ">1k<", ">10k<"})
        EXPECT_NE(doc.find(label), std::string::npos) << label;
    EXPECT_EQ(doc.find("front"), std::string::npos);
}

TEST(SvgPlotRender, ExtremeMagnitudesStayFinite) {
    PlotSpec spec;
    spec.paretoFront = true;
    spec.series.push_back(seriesOf("huge", {{-1.7e308, 1.7e308}, {1.7e308, -1.7e308}, {0, 0}}));
    spec.series.push_back(seriesOf("tiny", {{1e-310, 5e-324}}));
    expectValidDocument(renderSvg(spec));
    spec.logX = spec.logY = true;
    spec.series[0].points = {{1.7e308, 1e-300}, {5e-324, 1.7e308}};
    expectValidDocument(renderSvg(spec));
}

} // namespace
} // namespace glcollide::benchkit
