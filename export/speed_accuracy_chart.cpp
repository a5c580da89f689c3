#include "export/speed_accuracy_chart.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <glm/vec2.hpp>

#include "export/atomic_file.hpp"

namespace penink {

namespace {

struct Frame {  // plot area in SVG pixels and the log10 time range
    double left = 80, top = 60, right = 0, bottom = 0;
    double lo = 0, hi = 1;  // log10(ms)
    double x(double ms) const { return left + (std::log10(ms) - lo) / (hi - lo) * (right - left); }
    double y(double a) const { return bottom - std::clamp(a, 0.0, 1.0) * (bottom - top); }
};

std::string escape(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '&') o += "&amp;";
        else if (c == '<') o += "&lt;";
        else if (c == '>') o += "&gt;";
        else if (c == '"') o += "&quot;";
        else o += c;
    }
    return o;
}

std::string tick_label(double ms) {  // 0.5, 1, 2, 50, 1000
    std::ostringstream s;
    s << std::setprecision(ms < 1.0 ? 1 : 0) << std::fixed << ms;
    return s.str();
}

Frame plot_frame(const std::vector<ChartSeries>& series, const ChartText& text) {
    Frame f;
    std::size_t longest = 0;  // the legend's room: its longest name at ~7 px a character (12 px sans)
    for (const ChartSeries& c : series) longest = std::max(longest, c.name.size());
    f.right = text.width - std::max(230.0, 60.0 + 7.0 * double(longest)), f.bottom = text.height - 70.0;
    double lo = 1e300, hi = -1e300;
    for (const ChartSeries& s : series)
        for (const ChartPoint& p : s.points)
            for (double ms : {p.ms, p.ms_min, p.ms_max})
                if (ms > 0) lo = std::min(lo, ms), hi = std::max(hi, ms);
    if (lo > hi) lo = 1, hi = 1000;
    f.lo = std::floor(std::log10(lo)), f.hi = std::ceil(std::log10(hi));
    if (f.hi <= f.lo) f.hi = f.lo + 1;
    return f;
}

void axes(std::ostream& s, const Frame& f, const ChartText& text) {
    s << "<rect x=\"" << f.left << "\" y=\"" << f.top << "\" width=\"" << f.right - f.left << "\" height=\""
      << f.bottom - f.top << "\" fill=\"none\" stroke=\"#000000\"/>\n";
    for (int d = int(f.lo); d <= int(f.hi); ++d)
        for (double m : {1.0, 2.0, 5.0}) {
            const double ms = m * std::pow(10.0, d);
            if (std::log10(ms) > f.hi + 1e-9) break;
            const double x = f.x(ms);
            s << "<line x1=\"" << x << "\" y1=\"" << f.top << "\" x2=\"" << x << "\" y2=\"" << f.bottom
              << "\" stroke=\"#dddddd\"/>\n<text x=\"" << x << "\" y=\"" << f.bottom + 18
              << "\" text-anchor=\"middle\">" << tick_label(ms) << "</text>\n";
        }
    for (int i = 0; i <= 10; i += 2) {
        const double y = f.y(i / 10.0);
        s << "<line x1=\"" << f.left << "\" y1=\"" << y << "\" x2=\"" << f.right << "\" y2=\"" << y
          << "\" stroke=\"#dddddd\"/>\n<text x=\"" << f.left - 8 << "\" y=\"" << y + 4
          << "\" text-anchor=\"end\">" << i / 10.0 << "</text>\n";
    }
    s << "<text x=\"" << (f.left + f.right) / 2 << "\" y=\"" << f.bottom + 45 << "\" text-anchor=\"middle\">"
      << escape(text.x_label) << "</text>\n<text transform=\"translate(25," << (f.top + f.bottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << escape(text.y_label) << "</text>\n<text x=\""
      << text.width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"16\">" << escape(text.title)
      << "</text>\n<text x=\"" << text.width / 2 << "\" y=\"40\" text-anchor=\"middle\" font-size=\"11\">"
      << escape(text.subtitle) << "</text>\n";
}

void curve(std::ostream& s, const Frame& f, const ChartSeries& c) {
    s << "<g id=\"series-" << escape(c.name) << "\"><polyline fill=\"none\" stroke=\"" << c.colour
      << "\" stroke-width=\"2\"" << (c.dash.empty() ? "" : " stroke-dasharray=\"" + c.dash + "\"") << " points=\"";
    for (const ChartPoint& p : c.points)
        if (p.ms > 0) s << f.x(p.ms) << "," << f.y(p.accuracy) << " ";
    s << "\"/>\n";
    // A point drawn where the previous label would overlap its own shares it: "L2" + "L4" -> "L2,4".
    std::vector<std::pair<glm::dvec2, std::string>> labels;
    for (const ChartPoint& p : c.points) {
        if (p.ms <= 0) continue;
        const glm::dvec2 at(f.x(p.ms), f.y(p.accuracy));
        if (p.ms_min > 0 && p.ms_max > p.ms_min)
            s << "<path d=\"M" << f.x(p.ms_min) << "," << at.y - 3 << "v6M" << f.x(p.ms_min) << "," << at.y << "H"
              << f.x(p.ms_max) << "M" << f.x(p.ms_max) << "," << at.y - 3 << "v6\" stroke=\"" << c.colour
              << "\" stroke-width=\"1\" fill=\"none\"/>\n";
        s << "<circle cx=\"" << at.x << "\" cy=\"" << at.y << "\" r=\"3.5\" fill=\"" << c.colour << "\"/>\n";
        if (p.label.empty()) continue;
        if (!labels.empty() && std::abs(labels.back().first.x - at.x) < 20.0 && std::abs(labels.back().first.y - at.y) < 10.0)
            labels.back().second.append(",").append(p.label.substr(
                p.label.find_first_of("0123456789") == std::string::npos ? 0 : p.label.find_first_of("0123456789")));
        else
            labels.emplace_back(at, p.label);
    }
    for (const auto& [at, text] : labels)
        s << "<text x=\"" << at.x + 5 << "\" y=\"" << at.y - 5 << "\" font-size=\"10\">" << escape(text) << "</text>\n";
    s << "</g>\n";
}

void legend(std::ostream& s, const Frame& f, const std::vector<ChartSeries>& series) {
    double y = f.top + 10;
    for (const ChartSeries& c : series) {
        s << "<line x1=\"" << f.right + 20 << "\" y1=\"" << y << "\" x2=\"" << f.right + 50 << "\" y2=\"" << y
          << "\" stroke=\"" << c.colour << "\" stroke-width=\"2\""
          << (c.dash.empty() ? "" : " stroke-dasharray=\"" + c.dash + "\"") << "/>\n<text x=\"" << f.right + 56
          << "\" y=\"" << y + 4 << "\">" << escape(c.name) << "</text>\n";
        y += 20;
    }
}

}  // namespace

std::string speed_accuracy_svg(const std::vector<ChartSeries>& series, const ChartText& text) {
    const Frame f = plot_frame(series, text);
    std::ostringstream s;
    s << std::fixed << std::setprecision(1);
    s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\""
      << text.width << "\" height=\"" << text.height << "\" viewBox=\"0 0 " << text.width << " " << text.height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
    axes(s, f, text);
    for (const ChartSeries& c : series) curve(s, f, c);
    legend(s, f, series);
    s << "</svg>\n";
    return s.str();
}

void write_speed_accuracy_chart(const std::string& path, const std::vector<ChartSeries>& series,
                                const ChartText& text) {
    write_file_atomically(path, speed_accuracy_svg(series, text));
}

}  // namespace penink
