// isolux-cli sweep --chart (sweep_chart.hpp).
#include "cli/sweep_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string_view>

namespace isolux::cli {

namespace {

// Text for SVG: the five characters XML reserves, escaped.
std::string xml(std::string_view text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '&': out += "&amp;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += c;
        }
    }
    return out;
}

// A number with `precision` significant digits, as the sweep's CSV writes it.
std::string num(double v, int precision) {
    if (std::isinf(v)) return "inf";
    char text[64];
    std::snprintf(text, sizeof text, "%.*g", precision, v);
    return text;
}

}  // namespace

std::string sweep_svg(const std::vector<SweepAxis>& axes, const std::vector<SweepPoint>& points,
                      const std::string& title) {
    // The chart on the left, a table of every point on the right.
    const double CW = 760, H = std::max(480.0, 90 + 15.0 * double(points.size())), L = 70, R = 20, T = 64, B = 60;
    const double TW = 700, W = CW + TW;
    double tmin = 1e300, tmax = 0, emax = 0;
    for (const SweepPoint& p : points) {
        tmin = std::min(tmin, std::max(1e-4, p.lighting_min_ms));
        tmax = std::max(tmax, p.lighting_max_ms);
        emax = std::max(emax, p.final.rmse);
    }
    if (points.empty()) tmin = 0, tmax = 1;
    const bool log_x = tmin > 0 && tmax / tmin > 8;
    auto fx = [&](double t) {
        double u = log_x ? (std::log(std::max(t, 1e-4)) - std::log(tmin)) / std::max(1e-12, std::log(tmax) - std::log(tmin))
                         : (t - 0) / std::max(1e-12, tmax);
        return L + u * (CW - L - R);
    };
    emax = emax > 0 ? emax * 1.1 : 1;
    auto fy = [&](double e) { return H - B - e / emax * (H - T - B); };
    static const char* colours[] = {"#e07020", "#2a9d3a", "#8040c0", "#c02050"};
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << [&] {
             // The title, one <text> per line.
             std::ostringstream t;
             double y = 18;
             for (std::size_t pos = 0; pos <= title.size();) {
                 const std::size_t end = std::min(title.find('\n', pos), title.size());
                 t << "<text x=\"10\" y=\"" << y << "\" font-size=\"" << (y < 20 ? 14 : 11) << "\">"
                   << xml(title.substr(pos, end - pos)) << "</text>\n";
                 y += 16;
                 pos = end + 1;
             }
             return t.str();
         }()
      << "<line x1=\"" << L << "\" y1=\"" << H - B << "\" x2=\"" << CW - R << "\" y2=\"" << H - B << "\" stroke=\"black\"/>\n"
      << "<line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L << "\" y2=\"" << H - B << "\" stroke=\"black\"/>\n";
    for (int i = 0; i <= 4; ++i) {
        const double t = log_x ? tmin * std::pow(tmax / tmin, i / 4.0) : tmax * i / 4.0;
        const double e = emax * i / 4.0;
        s << "<text x=\"" << fx(t) << "\" y=\"" << H - B + 16 << "\" text-anchor=\"middle\">" << num(t, 3) << "</text>\n"
          << "<text x=\"" << L - 6 << "\" y=\"" << fy(e) + 4 << "\" text-anchor=\"end\">" << num(e, 3) << "</text>\n";
    }
    s << "<text x=\"" << (L + CW - R) / 2 << "\" y=\"" << H - 18
      << "\" text-anchor=\"middle\">lighting time per frame on the CPU (median of repeats; bar: min to max), ms"
      << (log_x ? " (log scale)" : "") << "</text>\n"
      << "<text transform=\"translate(16," << (T + H - B) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">final frame RMSE vs the reference (0-255)</text>\n";
    // One front per reference, never joined across references.
    const std::vector<const SweepPoint*> front = pareto_front(points);
    for (std::size_t i = 0; i < front.size();) {
        std::size_t j = i;
        s << "<polyline fill=\"none\" stroke=\"" << colours[int(front[i]->reference) % 4]
          << "\" stroke-width=\"1.5\" points=\"";
        for (; j < front.size() && front[j]->reference == front[i]->reference; ++j)
            s << fx(front[j]->lighting_ms) << "," << fy(front[j]->final.rmse) << " ";
        s << "\"/>\n";
        i = j;
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
        const SweepPoint& p = points[k];
        const char* colour = colours[int(p.reference) % 4];
        const double y = fy(p.final.rmse);
        s << "<line x1=\"" << fx(p.lighting_min_ms) << "\" y1=\"" << y << "\" x2=\"" << fx(p.lighting_max_ms) << "\" y2=\""
          << y << "\" stroke=\"#999\"/>\n"
          << "<circle cx=\"" << fx(p.lighting_ms) << "\" cy=\"" << y << "\" r=\"" << (p.pareto ? 4.5 : 3) << "\" fill=\""
          << (p.pareto ? colour : "#4070c0") << "\"/>\n"
          << "<text x=\"" << fx(p.lighting_ms) + 5 << "\" y=\"" << y - 5 << "\" font-size=\"9\">" << k + 1 << "</text>\n";
    }
    // The table: every point, numbered as on the chart.
    double ty = T;
    s << "<text x=\"" << CW + 10 << "\" y=\"" << ty << "\" font-weight=\"bold\">#  reference  ";
    for (const SweepAxis& a : axes) s << xml(a.name) << " ";
    s << " ms (min-max)  final RMSE  area RMSE floor/sprite</text>\n";
    for (std::size_t k = 0; k < points.size(); ++k) {
        const SweepPoint& p = points[k];
        ty += 15;
        s << "<text x=\"" << CW + 10 << "\" y=\"" << ty << "\" font-size=\"11\" fill=\""
          << (p.pareto ? colours[int(p.reference) % 4] : "black") << "\">" << k + 1 << "  " << to_string(p.reference) << "  ";
        for (const std::string& v : p.values) s << xml(v) << " ";
        s << " " << num(p.lighting_ms, 3) << " (" << num(p.lighting_min_ms, 3) << "-" << num(p.lighting_max_ms, 3) << ")  "
          << num(p.final.rmse, 3) << "  " << num(p.floor.rmse, 3) << "/" << num(p.sprite.rmse, 3) << "</text>\n";
    }
    s << "<text x=\"" << CW - R << "\" y=\"" << T - 14
      << "\" text-anchor=\"end\" font-size=\"11\">coloured: the Pareto front of each reference (least error for the "
         "time)</text>\n";
    s << "</svg>\n";
    return s.str();
}

}  // namespace isolux::cli
