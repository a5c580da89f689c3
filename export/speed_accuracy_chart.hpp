// The speed / accuracy chart of `penink bench`: an SVG line chart, time per frame (ms, log
// axis, decades labelled 1-2-5) against accuracy (0..1), one polyline per series with point
// markers, a horizontal bar from the fastest to the slowest run behind each marker where given,
// axis titles and a legend. Deterministic text (fixed precision) for tests and diffs.
#pragma once
#include <string>
#include <vector>

namespace penink {

struct ChartPoint {
    double ms = 0, accuracy = 0;
    double ms_min = 0, ms_max = 0;  // spread of the runs (min-max bar); 0 = no bar
    std::string label;  // drawn beside the marker (e.g. "L4"); "" = none
};

struct ChartSeries {
    std::string name;       // legend text
    std::string colour;     // "#rrggbb"
    std::string dash;       // SVG stroke-dasharray, "" = solid
    std::vector<ChartPoint> points;  // joined in this order
};

struct ChartText {
    std::string title, subtitle, x_label = "time per frame (ms, log scale)", y_label = "accuracy";
    int width = 900, height = 560;
};

// The SVG document. Points with ms <= 0 are left out (no place on a log axis).
std::string speed_accuracy_svg(const std::vector<ChartSeries>& series, const ChartText& text);

// Writes it atomically (export/atomic_file.hpp errors).
void write_speed_accuracy_chart(const std::string& path, const std::vector<ChartSeries>& series,
                                const ChartText& text);

}  // namespace penink
