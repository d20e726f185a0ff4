// svg.hpp - minimal inline SVG charts for self-contained HTML reports.
#pragma once
#include <string>
#include <vector>

namespace fracdesign {
namespace report {

struct Series {
    std::string label;
    std::string color;          // CSS colour
    std::vector<double> x, y;   // same length
};

struct Shade {
    double x0, x1;              // shaded x interval (e.g. a flagged time window)
    std::string label;
};

// Line chart, width x height pixels, linear axes with ticks, a legend, and
// optional shaded x intervals. Series longer than max_points are decimated
// by keeping the min and max of each bucket (peaks stay visible).
std::string line_chart(const std::string& title, const std::string& xlabel, const std::string& ylabel,
                       const std::vector<Series>& series, const std::vector<Shade>& shades = {}, bool logx = false,
                       bool logy = false, int width = 860, int height = 280, size_t max_points = 1600);

// Grouped bar chart: one group per category, one bar per series value.
std::string bar_chart(const std::string& title, const std::vector<std::string>& categories,
                      const std::vector<std::string>& series_labels, const std::vector<std::vector<double>>& values,
                      const std::vector<std::string>& colors, int width = 860, int height = 260);

std::string html_escape(const std::string& s);

}  // namespace report
}  // namespace fracdesign
