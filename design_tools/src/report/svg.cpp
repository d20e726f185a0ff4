// svg.cpp - inline SVG charts (see svg.hpp).
#include "fracdesign/report/svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace fracdesign {
namespace report {

std::string html_escape(const std::string& s)
{
    std::string o;
    for (char c : s) {
        switch (c) {
        case '&': o += "&amp;"; break;
        case '<': o += "&lt;"; break;
        case '>': o += "&gt;"; break;
        case '"': o += "&quot;"; break;
        default: o += c;
        }
    }
    return o;
}

namespace {

std::string fmt(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return b;
}

std::string px(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", v);
    return b;
}

// "Nice" tick positions covering [lo, hi].
std::vector<double> ticks(double lo, double hi, int n = 5)
{
    std::vector<double> t;
    const double span = hi - lo;
    if (!(span > 0)) return {lo};
    const double raw = span / n, mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * mag >= raw) {
            step = m * mag;
            break;
        }
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step) t.push_back(std::fabs(v) < 1e-12 * step ? 0.0 : v);
    return t;
}

}  // namespace

std::string line_chart(const std::string& title, const std::string& xlabel, const std::string& ylabel,
                       const std::vector<Series>& series, const std::vector<Shade>& shades, bool logx, bool logy,
                       int width, int height, size_t max_points)
{
    const double L = 70, R = 20, T = 28, B = 42;
    const double W = width - L - R, H = height - T - B;
    auto tx = [&](double v) { return logx ? std::log10(std::max(v, 1e-300)) : v; };
    auto ty = [&](double v) { return logy ? std::log10(std::max(v, 1e-300)) : v; };
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (const Series& s : series)
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (!std::isfinite(s.y[i]) || (logx && s.x[i] <= 0) || (logy && s.y[i] <= 0)) continue;
            x0 = std::min(x0, tx(s.x[i]));
            x1 = std::max(x1, tx(s.x[i]));
            y0 = std::min(y0, ty(s.y[i]));
            y1 = std::max(y1, ty(s.y[i]));
        }
    if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + (std::fabs(y0) > 0 ? std::fabs(y0) * 0.1 : 1.0);
    const double pad = 0.05 * (y1 - y0);
    y0 -= pad;
    y1 += pad;
    auto X = [&](double v) { return L + (tx(v) - x0) / (x1 - x0) * W; };
    auto Y = [&](double v) { return T + (1.0 - (ty(v) - y0) / (y1 - y0)) * H; };
    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    o << "<text x=\"" << L << "\" y=\"16\" font-size=\"13\" font-weight=\"bold\">" << html_escape(title) << "</text>\n";
    for (const Shade& s : shades) {
        const double a = std::max(L, X(s.x0)), b = std::min(L + W, X(s.x1));
        if (b <= a) continue;
        o << "<rect x=\"" << px(a) << "\" y=\"" << T << "\" width=\"" << px(b - a) << "\" height=\"" << H
          << "\" fill=\"#f4b400\" fill-opacity=\"0.25\"><title>" << html_escape(s.label) << "</title></rect>\n";
    }
    o << "<rect x=\"" << L << "\" y=\"" << T << "\" width=\"" << W << "\" height=\"" << H
      << "\" fill=\"none\" stroke=\"#888\"/>\n";
    for (double t : ticks(x0, x1)) {
        const double xv = logx ? std::pow(10.0, t) : t;
        o << "<line x1=\"" << px(X(xv)) << "\" x2=\"" << px(X(xv)) << "\" y1=\"" << T << "\" y2=\"" << T + H
          << "\" stroke=\"#eee\"/><text x=\"" << px(X(xv)) << "\" y=\"" << T + H + 14 << "\" text-anchor=\"middle\">"
          << fmt(xv) << "</text>\n";
    }
    for (double t : ticks(y0, y1)) {
        const double yv = logy ? std::pow(10.0, t) : t;
        o << "<line x1=\"" << L << "\" x2=\"" << L + W << "\" y1=\"" << px(Y(yv)) << "\" y2=\"" << px(Y(yv))
          << "\" stroke=\"#eee\"/><text x=\"" << L - 4 << "\" y=\"" << px(Y(yv) + 4) << "\" text-anchor=\"end\">"
          << fmt(yv) << "</text>\n";
    }
    o << "<text x=\"" << L + W / 2 << "\" y=\"" << height - 6 << "\" text-anchor=\"middle\">" << html_escape(xlabel)
      << "</text>\n";
    o << "<text transform=\"translate(14," << T + H / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
      << html_escape(ylabel) << "</text>\n";
    double lx = L + 8;
    for (const Series& s : series) {
        const size_t n = s.x.size();
        std::vector<size_t> keep;
        if (n <= max_points) {
            for (size_t i = 0; i < n; ++i) keep.push_back(i);
        } else {
            const size_t buckets = max_points / 2;
            for (size_t b = 0; b < buckets; ++b) {
                const size_t i0 = b * n / buckets, i1 = std::max(i0 + 1, (b + 1) * n / buckets);
                size_t imin = i0, imax = i0;
                for (size_t i = i0; i < i1 && i < n; ++i) {
                    if (s.y[i] < s.y[imin]) imin = i;
                    if (s.y[i] > s.y[imax]) imax = i;
                }
                keep.push_back(std::min(imin, imax));
                if (imin != imax) keep.push_back(std::max(imin, imax));
            }
        }
        o << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"1.2\" points=\"";
        for (size_t i : keep) {
            if (!std::isfinite(s.y[i]) || (logx && s.x[i] <= 0) || (logy && s.y[i] <= 0)) continue;
            o << px(X(s.x[i])) << "," << px(std::min(std::max(Y(s.y[i]), T), T + H)) << " ";
        }
        o << "\"/>\n";
        o << "<rect x=\"" << px(lx) << "\" y=\"" << T + 6 << "\" width=\"12\" height=\"3\" fill=\"" << s.color
          << "\"/><text x=\"" << px(lx + 16) << "\" y=\"" << T + 11 << "\">" << html_escape(s.label) << "</text>\n";
        lx += 24 + 6.5 * double(s.label.size());
    }
    o << "</svg>\n";
    return o.str();
}

std::string bar_chart(const std::string& title, const std::vector<std::string>& categories,
                      const std::vector<std::string>& series_labels, const std::vector<std::vector<double>>& values,
                      const std::vector<std::string>& colors, int width, int height)
{
    const double L = 70, R = 20, T = 28, B = 42;
    const double W = width - L - R, H = height - T - B;
    double vmax = 0;
    for (const auto& row : values)
        for (double v : row)
            if (std::isfinite(v)) vmax = std::max(vmax, v);
    if (vmax <= 0) vmax = 1;
    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    o << "<text x=\"" << L << "\" y=\"16\" font-size=\"13\" font-weight=\"bold\">" << html_escape(title) << "</text>\n";
    o << "<rect x=\"" << L << "\" y=\"" << T << "\" width=\"" << W << "\" height=\"" << H
      << "\" fill=\"none\" stroke=\"#888\"/>\n";
    for (double t : ticks(0, vmax)) {
        const double y = T + H - t / vmax * H;
        o << "<line x1=\"" << L << "\" x2=\"" << L + W << "\" y1=\"" << px(y) << "\" y2=\"" << px(y)
          << "\" stroke=\"#eee\"/><text x=\"" << L - 4 << "\" y=\"" << px(y + 4) << "\" text-anchor=\"end\">" << fmt(t)
          << "</text>\n";
    }
    const size_t nc = categories.size(), ns = series_labels.size();
    const double gw = W / double(std::max<size_t>(nc, 1)), bw = 0.8 * gw / double(std::max<size_t>(ns, 1));
    for (size_t c = 0; c < nc; ++c) {
        for (size_t s = 0; s < ns && s < values.size(); ++s) {
            const double v = c < values[s].size() && std::isfinite(values[s][c]) ? values[s][c] : 0.0;
            const double x = L + gw * double(c) + 0.1 * gw + bw * double(s), h = v / vmax * H;
            o << "<rect x=\"" << px(x) << "\" y=\"" << px(T + H - h) << "\" width=\"" << px(bw * 0.95)
              << "\" height=\"" << px(h) << "\" fill=\"" << colors[s % colors.size()] << "\"><title>"
              << html_escape(series_labels[s] + " " + categories[c] + ": " + fmt(v)) << "</title></rect>\n";
        }
        o << "<text x=\"" << px(L + gw * (double(c) + 0.5)) << "\" y=\"" << T + H + 14 << "\" text-anchor=\"middle\">"
          << html_escape(categories[c]) << "</text>\n";
    }
    double lx = L + 8;
    for (size_t s = 0; s < ns; ++s) {
        o << "<rect x=\"" << px(lx) << "\" y=\"" << T + 6 << "\" width=\"12\" height=\"8\" fill=\"" << colors[s % colors.size()]
          << "\"/><text x=\"" << px(lx + 16) << "\" y=\"" << T + 14 << "\">" << html_escape(series_labels[s]) << "</text>\n";
        lx += 24 + 6.5 * double(series_labels[s].size());
    }
    o << "</svg>\n";
    return o.str();
}

}  // namespace report
}  // namespace fracdesign
