#include "ui/AccuracyPlot.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>
#include <unordered_map>

#include "util/Error.h"
#include "util/FileInput.h"

namespace candela::ui {

// ---------------------------------------------------------------------------------------------
// Reading a benchmark's CSV.

namespace {

std::string_view trimmed(std::string_view s) {
    constexpr std::string_view kSpace = " \t\r\n";
    size_t begin = s.find_first_not_of(kSpace);
    if (begin == std::string_view::npos) return {};
    return s.substr(begin, s.find_last_not_of(kSpace) - begin + 1);
}

std::vector<std::string_view> splitFields(std::string_view line) {
    std::vector<std::string_view> fields;
    for (size_t start = 0;;) {
        size_t comma = line.find(',', start);
        fields.push_back(trimmed(line.substr(start, comma - start)));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

/// Where a bad value was found, for the error message.
struct CsvPlace {
    const std::string& file;
    int line = 0;  ///< 1-based, the header is line 1.
};

[[noreturn]] void rowError(const CsvPlace& at, const std::string& what) {
    throw InputError(at.file + ", line " + std::to_string(at.line) + ": " + what);
}

/// 'text' for messages (appended piecewise: GCC 12 at -O3 warns falsely on "'" + s + "'").
std::string quote(std::string_view text) {
    std::string q;
    q.reserve(text.size() + 2);
    q.push_back('\'');
    q.append(text);
    q.push_back('\'');
    return q;
}

/// A finite value >= 0 of column `column`.
double parseNonNegative(std::string_view text, const char* column, const CsvPlace& at) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    std::string quoted = quote(text);
    if (text.empty() || ec == std::errc::invalid_argument || ptr != end)
        rowError(at, std::string("column ") + column + ": expected a number, found " + quoted);
    if (ec == std::errc::result_out_of_range)
        rowError(at, std::string("column ") + column + ": " + quoted + " is out of range");
    if (!std::isfinite(value))
        rowError(at,
                 std::string("column ") + column + ": expected a finite number, found " + quoted);
    if (value < 0.0)
        rowError(at, std::string("column ") + column + ": expected a value >= 0, found " + quoted);
    return value;
}

/// A whole number >= 0 of column `column`.
int parseCount(std::string_view text, const char* column, const CsvPlace& at) {
    int value = 0;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    std::string quoted = quote(text);
    if (text.empty() || ec == std::errc::invalid_argument || ptr != end)
        rowError(at,
                 std::string("column ") + column + ": expected a whole number, found " + quoted);
    if (ec == std::errc::result_out_of_range)
        rowError(at, std::string("column ") + column + ": " + quoted + " is out of range");
    if (value < 0)
        rowError(at, std::string("column ") + column + ": expected a value >= 0, found " + quoted);
    return value;
}

/// Indices of the columns readBenchCsv uses, found by name in the header.
struct BenchColumns {
    size_t technique = 0, spp = 0, gpuMs = 0, relRmse = 0, deltaE = 0;
    size_t count = 0;  ///< Fields in the header, hence in every row.
};

BenchColumns findColumns(std::string_view header, const CsvPlace& at) {
    std::vector<std::string_view> names = splitFields(header);
    auto find = [&](std::string_view name) {
        auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end())
            rowError(at, "missing column '" + std::string(name) +
                             "' (the header needs technique, "
                             "spp, gpu_ms, rel_rmse and mean_delta_e)");
        return size_t(it - names.begin());
    };
    BenchColumns c;
    c.technique = find("technique");
    c.spp = find("spp");
    c.gpuMs = find("gpu_ms");
    c.relRmse = find("rel_rmse");
    c.deltaE = find("mean_delta_e");
    c.count = names.size();
    return c;
}

}  // namespace

std::vector<ErrorSeries> readBenchCsv(const std::filesystem::path& path) {
    std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw InputError(file + ": no such file (expected a benchmark CSV)");
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(file + ": not a regular file (expected a benchmark CSV)");
    std::istringstream in(readInputFile(file, "benchmark CSV", kMaxTextBytes));

    CsvPlace at{file, 0};
    std::string line;
    BenchColumns columns;
    bool haveHeader = false;
    std::vector<ErrorSeries> series;
    std::unordered_map<std::string, size_t> index;  // technique -> position in `series`
    while (std::getline(in, line)) {
        ++at.line;
        std::string_view text = trimmed(line);
        if (at.line == 1 && text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 BOM
        if (text.empty()) continue;
        if (!haveHeader) {
            columns = findColumns(text, at);
            haveHeader = true;
            continue;
        }
        std::vector<std::string_view> fields = splitFields(text);
        if (fields.size() != columns.count)
            rowError(at, "expected " + std::to_string(columns.count) +
                             " fields as in the header, found " + std::to_string(fields.size()));
        std::string technique(fields[columns.technique]);
        if (technique.empty()) rowError(at, "column technique: expected a name, found nothing");
        ErrorPoint p;
        p.spp = parseCount(fields[columns.spp], "spp", at);
        p.timeMs = parseNonNegative(fields[columns.gpuMs], "gpu_ms", at);
        p.relRmse = parseNonNegative(fields[columns.relRmse], "rel_rmse", at);
        p.deltaE = parseNonNegative(fields[columns.deltaE], "mean_delta_e", at);
        auto [it, added] = index.try_emplace(technique, series.size());
        if (added) series.push_back({technique + " (bench)", {}, true});
        series[it->second].points.push_back(p);
    }
    if (in.bad()) throw InputError(file + ": read error");
    if (!haveHeader)
        throw InputError(file +
                         ": empty file (expected a header line with technique, spp, gpu_ms, "
                         "rel_rmse and mean_delta_e)");
    return series;
}

// ---------------------------------------------------------------------------------------------
// Error at a time budget.

namespace {

/// A point reduced to what interpolation needs.
struct Sample {
    double timeMs;  ///< GPU time, ms.
    double error;   ///< The metric's value.
};

/// The points of a series with a finite time and a finite error, in their order.
std::vector<Sample> finiteSamples(const ErrorSeries& series, ErrorMetric metric) {
    std::vector<Sample> samples;
    samples.reserve(series.points.size());
    for (const ErrorPoint& p : series.points) {
        double e = metricOf(p, metric);
        if (std::isfinite(p.timeMs) && std::isfinite(e)) samples.push_back({p.timeMs, e});
    }
    return samples;
}

/// The error at timeMs between a and b (timeMs between their times): linear in log time vs log
/// error where both times and both errors are positive (exact on a power law), else linear.
double interpolate(const Sample& a, const Sample& b, double timeMs) {
    if (a.timeMs == b.timeMs) return b.error;
    double u;
    bool logLog = a.timeMs > 0.0 && b.timeMs > 0.0 && a.error > 0.0 && b.error > 0.0;
    if (logLog) {
        double la = std::log(a.timeMs), span = std::log(b.timeMs) - la;
        u = span != 0.0 ? (std::log(timeMs) - la) / span : 1.0;
    } else {
        u = (timeMs - a.timeMs) / (b.timeMs - a.timeMs);
    }
    u = std::isfinite(u) ? std::clamp(u, 0.0, 1.0) : 0.0;
    if (logLog) {
        double la = std::log(a.error), lb = std::log(b.error);
        return std::exp(la + u * (lb - la));
    }
    return a.error * (1.0 - u) + b.error * u;
}

}  // namespace

double metricOf(const ErrorPoint& p, ErrorMetric metric) {
    return metric == ErrorMetric::DeltaE ? p.deltaE : p.relRmse;
}

double errorAtTime(const ErrorSeries& series, double timeMs, ErrorMetric metric) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    std::vector<Sample> s = finiteSamples(series, metric);
    if (s.empty() || !(timeMs >= s.front().timeMs)) return kNaN;  // also a NaN timeMs
    // The first segment around timeMs (times may step back a little in a measured series).
    for (size_t k = 0; k + 1 < s.size(); ++k) {
        double lo = std::min(s[k].timeMs, s[k + 1].timeMs),
               hi = std::max(s[k].timeMs, s[k + 1].timeMs);
        if (timeMs >= lo && timeMs <= hi) return interpolate(s[k], s[k + 1], timeMs);
    }
    // Past every point: the technique stopped at its latest point of largest time.
    size_t last = 0;
    for (size_t k = 1; k < s.size(); ++k)
        if (s[k].timeMs >= s[last].timeMs) last = k;
    return s[last].error;
}

Winner winnerAt(const std::vector<ErrorSeries>& series, double timeMs, ErrorMetric metric) {
    Winner best;
    for (size_t k = 0; k < series.size(); ++k) {
        double e = errorAtTime(series[k], timeMs, metric);
        if (std::isnan(e)) continue;
        if (best.series < 0 || e < best.error) best = {int(k), e};
    }
    return best;
}

// ---------------------------------------------------------------------------------------------
// Labels and colours.

ImU32 seriesColour(size_t index) {
    static constexpr ImU32 kPalette[] = {
        IM_COL32(255, 150, 40, 255),   // orange
        IM_COL32(90, 170, 255, 255),   // blue
        IM_COL32(110, 210, 90, 255),   // green
        IM_COL32(240, 80, 90, 255),    // red
        IM_COL32(190, 125, 255, 255),  // violet
        IM_COL32(240, 220, 70, 255),   // yellow
        IM_COL32(70, 215, 205, 255),   // teal
        IM_COL32(250, 135, 200, 255),  // pink
    };
    return kPalette[index % std::size(kPalette)];
}

namespace {

/// A time in ms or s with `digits` significant digits.
std::string timeLabel(double ms, int digits) {
    char text[64];
    if (std::abs(ms) >= 1000.0)
        std::snprintf(text, sizeof text, "%.*g s", digits, ms / 1000.0);
    else
        std::snprintf(text, sizeof text, "%.*g ms", digits, ms);
    return text;
}

/// A value of the metric (relative RMSE in percent) with `digits` significant digits.
std::string metricLabel(double value, ErrorMetric metric, int digits) {
    char text[64];
    if (metric == ErrorMetric::RelRmse)
        std::snprintf(text, sizeof text, "%.*g%%", digits, value * 100.0);
    else
        std::snprintf(text, sizeof text, "%.*g", digits, value);
    return text;
}

}  // namespace

std::string timeTickLabel(double ms) {
    return timeLabel(ms, 6);
}

std::string metricTickLabel(double value, ErrorMetric metric) {
    return metricLabel(value, metric, 6);
}

// ---------------------------------------------------------------------------------------------
// Drawing.

namespace {

constexpr ImU32 kBackground = IM_COL32(20, 22, 26, 255);
constexpr ImU32 kFrameColour = IM_COL32(255, 255, 255, 70);
constexpr ImU32 kGridColour = IM_COL32(255, 255, 255, 45);
constexpr ImU32 kMinorGridColour = IM_COL32(255, 255, 255, 18);
constexpr ImU32 kLabelColour = IM_COL32(220, 220, 220, 210);
constexpr ImU32 kBudgetColour = IM_COL32(255, 255, 255, 150);
constexpr float kHoverRadius = 8.f;  ///< Mouse distance to a point that shows its tooltip, px.

/// Whether a point can be placed on log-log axes.
bool plottable(const ErrorPoint& p, ErrorMetric metric) {
    double e = metricOf(p, metric);
    return std::isfinite(p.timeMs) && p.timeMs > 0.0 && std::isfinite(e) && e > 0.0;
}

/// The log-log mapping of the plot area.
struct Axes {
    ImVec2 min, max;        ///< Plot area on screen, px.
    double x0 = 0, x1 = 1;  ///< Time range, log10 of ms (whole decades).
    double y0 = 0, y1 = 1;  ///< Error range, log10 of the metric (whole decades).

    float screenX(double ms) const { return along(std::log10(ms), x0, x1, min.x, max.x); }
    float screenY(double error) const { return along(std::log10(error), y0, y1, max.y, min.y); }
    ImVec2 screen(double ms, double error) const { return ImVec2(screenX(ms), screenY(error)); }

  private:
    /// Pixel of log value v between a (at pixel pa) and b (pb), kept near the area.
    static float along(double v, double a, double b, float pa, float pb) {
        double f = std::clamp((v - a) / (b - a), -4.0, 5.0);
        return pa + float(f) * (pb - pa);
    }
};

/// Whole decades [lo, hi] of log10 around the values in [minValue, maxValue], at least one wide.
void decadeRange(double minValue, double maxValue, double& lo, double& hi) {
    lo = std::floor(std::log10(minValue));
    hi = std::ceil(std::log10(maxValue));
    if (hi <= lo) hi = lo + 1.0;
}

/// Decade step between labelled grid lines so that at most about ten are drawn.
int decadeStride(double lo, double hi) {
    return std::max(1, (int(hi - lo) + 9) / 10);
}

std::string timeText(double ms) {
    return timeLabel(ms, 4);
}

std::string errorText(double value, ErrorMetric metric) {
    return metricLabel(value, metric, 3);
}

void addText(ImDrawList* draw, ImVec2 at, ImU32 colour, const std::string& text) {
    draw->AddText(at, colour, text.c_str(), text.c_str() + text.size());
}

/// Width of the widest error label, px.
float errorLabelWidth(const Axes& axes, ErrorMetric metric) {
    float width = 0.f;
    for (int k = int(axes.y0); k <= int(axes.y1); k += decadeStride(axes.y0, axes.y1))
        width = std::max(width,
                         ImGui::CalcTextSize(metricTickLabel(std::pow(10.0, k), metric).c_str()).x);
    return width;
}

/// Decade lines with labels, minor lines (2..9 times a decade) when few decades are shown.
void drawGrid(ImDrawList* draw, const Axes& a, ErrorMetric metric) {
    float lineHeight = ImGui::GetTextLineHeight();
    bool minorX = a.x1 - a.x0 <= 4.0, minorY = a.y1 - a.y0 <= 4.0;
    for (int k = int(a.x0); k <= int(a.x1); ++k) {
        double decade = std::pow(10.0, k);
        for (int m = 2; minorX && k < int(a.x1) && m <= 9; ++m) {
            float x = a.screenX(m * decade);
            draw->AddLine(ImVec2(x, a.min.y), ImVec2(x, a.max.y), kMinorGridColour);
        }
        if ((k - int(a.x0)) % decadeStride(a.x0, a.x1) != 0) continue;
        float x = a.screenX(decade);
        draw->AddLine(ImVec2(x, a.min.y), ImVec2(x, a.max.y), kGridColour);
        std::string label = timeTickLabel(decade);
        float w = ImGui::CalcTextSize(label.c_str()).x;
        // Centred on the line, but kept clear of the error labels and inside the frame.
        float left = std::max(std::min(x - 0.5f * w, a.max.x - w), a.min.x);
        addText(draw, ImVec2(left, a.max.y + 2.f), kLabelColour, label);
    }
    for (int k = int(a.y0); k <= int(a.y1); ++k) {
        double decade = std::pow(10.0, k);
        for (int m = 2; minorY && k < int(a.y1) && m <= 9; ++m) {
            float y = a.screenY(m * decade);
            draw->AddLine(ImVec2(a.min.x, y), ImVec2(a.max.x, y), kMinorGridColour);
        }
        if ((k - int(a.y0)) % decadeStride(a.y0, a.y1) != 0) continue;
        float y = a.screenY(decade);
        draw->AddLine(ImVec2(a.min.x, y), ImVec2(a.max.x, y), kGridColour);
        std::string label = metricTickLabel(decade, metric);
        float w = ImGui::CalcTextSize(label.c_str()).x;
        addText(draw, ImVec2(a.min.x - w - 4.f, y - 0.5f * lineHeight), kLabelColour, label);
    }
    draw->AddRect(a.min, a.max, kFrameColour);
}

void addDashedLine(ImDrawList* draw, ImVec2 a, ImVec2 b, ImU32 colour, float thickness) {
    constexpr float kDash = 6.f, kGap = 4.f;  ///< px
    float dx = b.x - a.x, dy = b.y - a.y, length = std::sqrt(dx * dx + dy * dy);
    if (!(length > 0.f)) return;
    if (length > 1e5f) return draw->AddLine(a, b, colour, thickness);  // not worth a dash loop
    for (float s = 0.f; s < length; s += kDash + kGap) {
        float e = std::min(s + kDash, length);
        draw->AddLine(ImVec2(a.x + dx * s / length, a.y + dy * s / length),
                      ImVec2(a.x + dx * e / length, a.y + dy * e / length), colour, thickness);
    }
}

/// One series: its polyline (dashed from a bench) and a marker on every point.
void drawSeries(ImDrawList* draw, const Axes& axes, const ErrorSeries& series, ErrorMetric metric,
                ImU32 colour, bool winner) {
    std::vector<ImVec2> points;
    for (const ErrorPoint& p : series.points)
        if (plottable(p, metric)) points.push_back(axes.screen(p.timeMs, metricOf(p, metric)));
    float thickness = winner ? 3.f : 1.5f, radius = winner ? 3.5f : 2.5f;
    if (series.fromBench) {
        for (size_t k = 0; k + 1 < points.size(); ++k)
            addDashedLine(draw, points[k], points[k + 1], colour, thickness);
    } else if (points.size() >= 2) {
        draw->AddPolyline(points.data(), int(points.size()), colour, ImDrawFlags_None, thickness);
    }
    for (ImVec2 p : points) {
        if (series.fromBench)
            draw->AddCircle(p, radius, colour, 12, 1.5f);
        else
            draw->AddCircleFilled(p, radius, colour, 12);
    }
}

/// The budget line with its label, and the winner's error on it.
void drawBudget(ImDrawList* draw, const Axes& axes, double budgetMs, const Winner& winner,
                ErrorMetric metric) {
    float x = axes.screenX(budgetMs), lineHeight = ImGui::GetTextLineHeight();
    draw->AddLine(ImVec2(x, axes.min.y), ImVec2(x, axes.max.y), kBudgetColour, 1.5f);
    addText(draw, ImVec2(x + 4.f, axes.max.y - lineHeight - 2.f), kBudgetColour,
            "budget " + timeText(budgetMs));
    if (winner.series < 0 || !(winner.error > 0.0) || !std::isfinite(winner.error)) return;
    ImVec2 p = axes.screen(budgetMs, winner.error);
    ImU32 colour = seriesColour(size_t(winner.series));
    draw->AddCircle(p, 6.f, IM_COL32(255, 255, 255, 230), 16, 2.f);
    draw->AddCircleFilled(p, 4.f, colour, 16);
    std::string value = errorText(winner.error, metric);
    ImVec2 at(p.x + 8.f, p.y - lineHeight - 1.f), size = ImGui::CalcTextSize(value.c_str());
    draw->AddRectFilled(ImVec2(at.x - 2.f, at.y), ImVec2(at.x + size.x + 2.f, at.y + size.y),
                        IM_COL32(20, 22, 26, 200), 2.f);
    addText(draw, at, colour, value);
}

/// Label and colour swatch of every series, in the top right corner of the plot area.
void drawLegend(ImDrawList* draw, const Axes& axes, const std::vector<ErrorSeries>& series,
                ErrorMetric metric, int winner) {
    float lineHeight = ImGui::GetTextLineHeight(), swatch = 2.f * lineHeight, pad = 4.f;
    float width = 0.f;
    for (const ErrorSeries& s : series)
        width = std::max(width, ImGui::CalcTextSize(s.label.c_str()).x);
    width += swatch + 3.f * pad;
    float height = float(series.size()) * lineHeight + 2.f * pad;
    // Top right, where convergence curves seldom go, unless more points lie there than bottom left.
    ImVec2 topRight(axes.max.x - width - pad, axes.min.y + pad);
    ImVec2 bottomLeft(axes.min.x + pad, axes.max.y - height - pad);
    auto pointsUnder = [&](ImVec2 corner) {
        int count = 0;
        for (const ErrorSeries& s : series)
            for (const ErrorPoint& p : s.points) {
                if (!plottable(p, metric)) continue;
                ImVec2 q = axes.screen(p.timeMs, metricOf(p, metric));
                count += q.x >= corner.x && q.x <= corner.x + width && q.y >= corner.y &&
                         q.y <= corner.y + height;
            }
        return count;
    };
    ImVec2 corner = pointsUnder(topRight) > pointsUnder(bottomLeft) ? bottomLeft : topRight;
    draw->AddRectFilled(corner, ImVec2(corner.x + width, corner.y + height),
                        IM_COL32(20, 22, 26, 200), 3.f);
    for (size_t k = 0; k < series.size(); ++k) {
        float y = corner.y + pad + k * lineHeight;
        ImVec2 a(corner.x + pad, y + 0.5f * lineHeight), b(a.x + swatch, a.y);
        float thickness = int(k) == winner ? 3.f : 1.5f;
        if (series[k].fromBench)
            addDashedLine(draw, a, b, seriesColour(k), thickness);
        else
            draw->AddLine(a, b, seriesColour(k), thickness);
        addText(draw, ImVec2(b.x + pad, y), kLabelColour, series[k].label);
    }
}

/// Tooltip of the point nearest the mouse, if within kHoverRadius.
void drawTooltip(ImDrawList* draw, const Axes& axes, const std::vector<ErrorSeries>& series,
                 ErrorMetric metric) {
    ImVec2 mouse = ImGui::GetMousePos();
    float best = kHoverRadius * kHoverRadius;
    const ErrorSeries* hit = nullptr;
    const ErrorPoint* point = nullptr;
    ImVec2 at;
    for (const ErrorSeries& s : series)
        for (const ErrorPoint& p : s.points) {
            if (!plottable(p, metric)) continue;
            ImVec2 q = axes.screen(p.timeMs, metricOf(p, metric));
            float d2 = (q.x - mouse.x) * (q.x - mouse.x) + (q.y - mouse.y) * (q.y - mouse.y);
            if (d2 < best) {
                best = d2;
                hit = &s;
                point = &p;
                at = q;
            }
        }
    if (!point) return;
    draw->AddCircle(at, 6.f, IM_COL32(255, 255, 255, 230), 16, 1.5f);
    ImGui::BeginTooltip();
    ImGui::TextUnformatted(hit->label.c_str());
    ImGui::Text("spp: %d", point->spp);
    ImGui::Text("time: %s", timeText(point->timeMs).c_str());
    ImGui::Text("rel. RMSE: %.3g%%", point->relRmse * 100.0);
    ImGui::Text("Delta E: %.3g", point->deltaE);
    ImGui::EndTooltip();
}

/// The item's size: `size` where positive, else the available room (a default height if none).
ImVec2 plotSize(ImVec2 size) {
    ImVec2 avail = ImGui::GetContentRegionAvail();
    auto pick = [](float wanted, float room, float fallback) {
        if (wanted > 0.f && std::isfinite(wanted)) return wanted;
        return room >= 1.f && std::isfinite(room) ? room : fallback;
    };
    float lineHeight = ImGui::GetTextLineHeight();
    return ImVec2(pick(size.x, avail.x, 30.f * lineHeight),
                  pick(size.y, avail.y, 15.f * lineHeight));
}

}  // namespace

void accuracyPlot(const char* id, const std::vector<ErrorSeries>& series, ErrorMetric metric,
                  double budgetMs, ImVec2 size) {
    ImGui::InvisibleButton(id, plotSize(size));
    bool hovered = ImGui::IsItemHovered();
    ImVec2 p0 = ImGui::GetItemRectMin(), p1 = ImGui::GetItemRectMax();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->PushClipRect(p0, p1, true);
    draw->AddRectFilled(p0, p1, kBackground);

    double tMin = HUGE_VAL, tMax = -HUGE_VAL, eMin = HUGE_VAL, eMax = -HUGE_VAL;
    for (const ErrorSeries& s : series)
        for (const ErrorPoint& p : s.points)
            if (plottable(p, metric)) {
                double e = metricOf(p, metric);
                tMin = std::min(tMin, p.timeMs), tMax = std::max(tMax, p.timeMs);
                eMin = std::min(eMin, e), eMax = std::max(eMax, e);
            }
    float lineHeight = ImGui::GetTextLineHeight();
    if (tMin > tMax) {
        const char* text = "no measurements yet";
        ImVec2 t = ImGui::CalcTextSize(text);
        draw->AddRect(p0, p1, kFrameColour);
        draw->AddText(ImVec2(0.5f * (p0.x + p1.x - t.x), 0.5f * (p0.y + p1.y - t.y)), kLabelColour,
                      text);
        draw->PopClipRect();
        return;
    }
    bool hasBudget = std::isfinite(budgetMs) && budgetMs > 0.0;
    if (hasBudget) tMin = std::min(tMin, budgetMs), tMax = std::max(tMax, budgetMs);

    Axes axes;
    decadeRange(tMin, tMax, axes.x0, axes.x1);
    decadeRange(eMin, eMax, axes.y0, axes.y1);
    axes.min = ImVec2(p0.x + errorLabelWidth(axes, metric) + 8.f, p0.y + 1.8f * lineHeight);
    axes.max = ImVec2(p1.x - 0.5f * lineHeight, p1.y - 2.5f * lineHeight);
    addText(draw, ImVec2(p0.x + 4.f, p0.y + 2.f), kLabelColour,
            metric == ErrorMetric::RelRmse ? "rel. RMSE" : "mean dE");
    float titleWidth = ImGui::CalcTextSize("GPU time").x;
    addText(draw, ImVec2(0.5f * (axes.min.x + axes.max.x - titleWidth), p1.y - lineHeight - 2.f),
            kLabelColour, "GPU time");
    if (axes.max.x - axes.min.x < 8.f || axes.max.y - axes.min.y < 8.f) {  // too small to plot
        draw->PopClipRect();
        return;
    }
    drawGrid(draw, axes, metric);

    Winner winner = hasBudget ? winnerAt(series, budgetMs, metric) : Winner{};
    draw->PushClipRect(axes.min, axes.max, true);
    for (size_t k = 0; k < series.size(); ++k)
        drawSeries(draw, axes, series[k], metric, seriesColour(k), int(k) == winner.series);
    if (hasBudget) drawBudget(draw, axes, budgetMs, winner, metric);
    drawLegend(draw, axes, series, metric, winner.series);
    if (hovered) drawTooltip(draw, axes, series, metric);
    draw->PopClipRect();
    draw->PopClipRect();
}

}  // namespace candela::ui
