#include "drapelab/report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "drapelab/report/axis_ticks.hpp"

namespace drapelab::report {
namespace {

// Layout in SVG user units (CSS pixels at 100 % zoom).
constexpr double kWidth = 560.0;  // two plots side by side in a 1200 px window
constexpr double kLeft = 80.0;    // room for y tick labels and the rotated y title
constexpr double kRight = 18.0;
constexpr double kTop = 34.0;  // room for the plot title
constexpr double kPlotHeight = 230.0;
constexpr double kLegendTop = kTop + kPlotHeight + 56.0;  // below the x tick labels and x title
constexpr double kLegendRow = 18.0;
constexpr double kCharWidth = 6.6;  // average width of an 11 px sans-serif character
constexpr double kPlotWidth = kWidth - kLeft - kRight;

std::string fixed(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
  return buffer;
}

// Maps data to the plot area.
struct Frame {
  AxisTicks x, y;
  double px(double v) const {
    const double t =
        x.log ? (std::log10(v) - std::log10(x.lo)) / (std::log10(x.hi) - std::log10(x.lo))
              : (v - x.lo) / (x.hi - x.lo);
    return kLeft + t * kPlotWidth;
  }
  double py(double v) const {
    return kTop + kPlotHeight - (v - y.lo) / (y.hi - y.lo) * kPlotHeight;
  }
};

bool usable_x(const Plot& plot, double x) { return std::isfinite(x) && (!plot.log_x || x > 0.0); }

void cross(std::ostringstream& out, double cx, double cy, const std::string& color) {
  const double r = 4.5;
  out << "<path class=\"failed-marker\" d=\"M" << fixed(cx - r) << ' ' << fixed(cy - r) << "L"
      << fixed(cx + r) << ' ' << fixed(cy + r) << "M" << fixed(cx - r) << ' ' << fixed(cy + r)
      << "L" << fixed(cx + r) << ' ' << fixed(cy - r) << "\" stroke=\"" << color
      << "\" stroke-width=\"2.2\" fill=\"none\"/>\n";
}

void end_marker(std::ostringstream& out, double cx, double cy, const std::string& color) {
  out << "<rect class=\"stop-marker\" x=\"" << fixed(cx - 4) << "\" y=\"" << fixed(cy - 4)
      << "\" width=\"8\" height=\"8\" fill=\"" << color
      << "\" stroke=\"#000\" stroke-width=\"1\"/>\n";
}

void draw_series(std::ostringstream& out, const Plot& plot, const Frame& frame, const Series& s) {
  out << "<g class=\"series\" data-label=\"" << escape_xml(s.label) << "\">\n";
  std::vector<std::pair<double, double>> segment;  // pixel points of the current unbroken piece
  double last_x = std::numeric_limits<double>::quiet_NaN(), last_y = last_x;
  auto flush = [&] {
    if (segment.size() == 1) {
      out << "<circle cx=\"" << fixed(segment[0].first) << "\" cy=\"" << fixed(segment[0].second)
          << "\" r=\"2\" fill=\"" << s.color << "\"/>\n";
    } else if (segment.size() > 1) {
      out << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"1.8\"";
      if (!s.dash.empty()) out << " stroke-dasharray=\"" << s.dash << "\"";
      out << " points=\"";
      for (std::size_t k = 0; k < segment.size(); ++k)
        out << (k ? " " : "") << fixed(segment[k].first) << ',' << fixed(segment[k].second);
      out << "\"/>\n";
    }
    segment.clear();
  };
  const std::size_t n = std::min(s.x.size(), s.y.size());
  for (std::size_t k = 0; k < n; ++k) {
    const bool failed = k < s.failed.size() && s.failed[k];
    if (!usable_x(plot, s.x[k])) {
      flush();
      continue;
    }
    if (failed) {
      // A failed run breaks the line; its cross sits at its value, or on the x axis when it has
      // none.
      flush();
      const double cy = std::isfinite(s.y[k]) ? frame.py(s.y[k]) : kTop + kPlotHeight;
      cross(out, frame.px(s.x[k]), cy, s.color);
      continue;
    }
    if (!std::isfinite(s.y[k])) {
      flush();
      continue;
    }
    const double px = frame.px(s.x[k]), py = frame.py(s.y[k]);
    segment.emplace_back(px, py);
    if (s.point_markers)
      out << "<circle cx=\"" << fixed(px) << "\" cy=\"" << fixed(py) << "\" r=\"3\" fill=\""
          << s.color << "\"/>\n";
    last_x = px;
    last_y = py;
  }
  flush();
  if (s.stopped_early && std::isfinite(last_x)) end_marker(out, last_x, last_y, s.color);
  out << "</g>\n";
}

}  // namespace

std::string escape_xml(const std::string& text) {
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
      default:
        out += c;
    }
  }
  return out;
}

std::string svg_plot(const Plot& plot, bool standalone) {
  // Data range over every drawable point (failed points count on x only).
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, y_min = x_min,
         y_max = -x_min;
  bool any_failed = false, any_stopped = false;
  for (const auto& s : plot.series) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t k = 0; k < n; ++k) {
      if (!usable_x(plot, s.x[k])) continue;
      const bool failed = k < s.failed.size() && s.failed[k];
      if (!failed && !std::isfinite(s.y[k])) continue;
      x_min = std::min(x_min, s.x[k]);
      x_max = std::max(x_max, s.x[k]);
      any_failed = any_failed || failed;
      if (std::isfinite(s.y[k])) {
        y_min = std::min(y_min, s.y[k]);
        y_max = std::max(y_max, s.y[k]);
      }
    }
    any_stopped = any_stopped || s.stopped_early;
  }
  const bool has_data = std::isfinite(y_min);

  Frame frame;
  if (!plot.x_categories.empty()) {
    frame.x.lo = -0.5;
    frame.x.hi = static_cast<double>(plot.x_categories.size()) - 0.5;
    for (std::size_t k = 0; k < plot.x_categories.size(); ++k) {
      frame.x.values.push_back(static_cast<double>(k));
      frame.x.labels.push_back(plot.x_categories[k]);
    }
  } else {
    frame.x = plot.log_x ? log_ticks(x_min, x_max) : linear_ticks(x_min, x_max, 6);
  }
  frame.y = linear_ticks(y_min, y_max, 5);

  // Legend entries: every series, then the marker keys that appear.
  struct Entry {
    std::string label, kind, color, dash;
  };
  std::vector<Entry> entries;
  for (const auto& s : plot.series) entries.push_back({s.label, "line", s.color, s.dash});
  if (any_failed) entries.push_back({"failed run (status not ok)", "cross", "#444", ""});
  if (any_stopped) entries.push_back({"stopped early (status not ok)", "stop", "#888", ""});
  std::vector<std::pair<double, double>> positions;  // legend item origins
  double cursor_x = kLeft, cursor_y = kLegendTop;
  for (const auto& e : entries) {
    const double item_width = 34.0 + kCharWidth * static_cast<double>(e.label.size()) + 18.0;
    if (cursor_x > kLeft && cursor_x + item_width > kWidth - kRight) {
      cursor_x = kLeft;
      cursor_y += kLegendRow;
    }
    positions.emplace_back(cursor_x, cursor_y);
    cursor_x += item_width;
  }
  const double height = (entries.empty() ? kLegendTop : cursor_y + kLegendRow) + 6.0;

  std::ostringstream out;
  if (standalone) out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<svg class=\"plot\"" << (standalone ? " xmlns=\"http://www.w3.org/2000/svg\"" : "")
      << " width=\"" << fixed(kWidth) << "\" height=\"" << fixed(height) << "\" viewBox=\"0 0 "
      << fixed(kWidth) << ' ' << fixed(height) << "\" role=\"img\" aria-label=\""
      << escape_xml(plot.title)
      << "\" font-family=\"DejaVu Sans, Arial, Helvetica, sans-serif\" font-size=\"11\">\n";
  out << "<title>" << escape_xml(plot.title) << "</title>\n";
  out << "<rect x=\"0\" y=\"0\" width=\"" << fixed(kWidth) << "\" height=\"" << fixed(height)
      << "\" fill=\"#fff\"/>\n";
  out << "<text class=\"plot-title\" x=\"" << fixed(kLeft + kPlotWidth / 2)
      << "\" y=\"20\" text-anchor=\"middle\""
      << " font-size=\"13\" font-weight=\"bold\">" << escape_xml(plot.title) << "</text>\n";

  // Grid, then axes with ticks and labels.
  out << "<g class=\"grid\" stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
  for (const double v : frame.y.values)
    out << "<line x1=\"" << fixed(kLeft) << "\" x2=\"" << fixed(kLeft + kPlotWidth) << "\" y1=\""
        << fixed(frame.py(v)) << "\" y2=\"" << fixed(frame.py(v)) << "\"/>\n";
  for (const double v : frame.x.values)
    out << "<line x1=\"" << fixed(frame.px(v)) << "\" x2=\"" << fixed(frame.px(v)) << "\" y1=\""
        << fixed(kTop) << "\" y2=\"" << fixed(kTop + kPlotHeight) << "\"/>\n";
  out << "</g>\n";

  const double bottom = kTop + kPlotHeight;
  out << "<g class=\"x-axis\">\n<line class=\"axis-line\" x1=\"" << fixed(kLeft) << "\" x2=\""
      << fixed(kLeft + kPlotWidth) << "\" y1=\"" << fixed(bottom) << "\" y2=\"" << fixed(bottom)
      << "\" stroke=\"#000\"/>\n";
  for (std::size_t k = 0; k < frame.x.values.size(); ++k) {
    const double px = frame.px(frame.x.values[k]);
    out << "<line class=\"tick\" x1=\"" << fixed(px) << "\" x2=\"" << fixed(px) << "\" y1=\""
        << fixed(bottom) << "\" y2=\"" << fixed(bottom + 5) << "\" stroke=\"#000\"/>\n"
        << "<text class=\"tick-label\" x=\"" << fixed(px) << "\" y=\"" << fixed(bottom + 18)
        << "\" text-anchor=\"middle\">" << escape_xml(frame.x.labels[k]) << "</text>\n";
  }
  out << "<text class=\"axis-title\" x=\"" << fixed(kLeft + kPlotWidth / 2) << "\" y=\""
      << fixed(bottom + 38) << "\" text-anchor=\"middle\" font-size=\"12\">"
      << escape_xml(plot.x_title) << "</text>\n</g>\n";

  out << "<g class=\"y-axis\">\n<line class=\"axis-line\" x1=\"" << fixed(kLeft) << "\" x2=\""
      << fixed(kLeft) << "\" y1=\"" << fixed(kTop) << "\" y2=\"" << fixed(bottom)
      << "\" stroke=\"#000\"/>\n";
  for (std::size_t k = 0; k < frame.y.values.size(); ++k) {
    const double py = frame.py(frame.y.values[k]);
    out << "<line class=\"tick\" x1=\"" << fixed(kLeft - 5) << "\" x2=\"" << fixed(kLeft)
        << "\" y1=\"" << fixed(py) << "\" y2=\"" << fixed(py) << "\" stroke=\"#000\"/>\n"
        << "<text class=\"tick-label\" x=\"" << fixed(kLeft - 8) << "\" y=\"" << fixed(py + 4)
        << "\" text-anchor=\"end\">" << escape_xml(frame.y.labels[k]) << "</text>\n";
  }
  const double title_y = kTop + kPlotHeight / 2;
  out << "<text class=\"axis-title\" x=\"16\" y=\"" << fixed(title_y)
      << "\" transform=\"rotate(-90 16 " << fixed(title_y)
      << ")\" text-anchor=\"middle\" font-size=\"12\">" << escape_xml(plot.y_title)
      << "</text>\n</g>\n";

  if (!has_data)
    out << "<text class=\"no-data\" x=\"" << fixed(kLeft + kPlotWidth / 2) << "\" y=\""
        << fixed(title_y) << "\" text-anchor=\"middle\" fill=\"#888\">no data</text>\n";
  for (const auto& s : plot.series) draw_series(out, plot, frame, s);

  out << "<g class=\"legend\">\n";
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const auto& e = entries[k];
    const double x = positions[k].first, y = positions[k].second;
    if (e.kind == "line") {
      out << "<line x1=\"" << fixed(x) << "\" x2=\"" << fixed(x + 26) << "\" y1=\"" << fixed(y)
          << "\" y2=\"" << fixed(y) << "\" stroke=\"" << e.color << "\" stroke-width=\"2.5\"";
      if (!e.dash.empty()) out << " stroke-dasharray=\"" << e.dash << "\"";
      out << "/>\n";
    } else if (e.kind == "cross") {
      cross(out, x + 13, y, e.color);
    } else {
      end_marker(out, x + 13, y, e.color);
    }
    out << "<text class=\"legend-label\" x=\"" << fixed(x + 32) << "\" y=\"" << fixed(y + 4)
        << "\">" << escape_xml(e.label) << "</text>\n";
  }
  out << "</g>\n</svg>\n";
  return out.str();
}

const std::string& palette_color(std::size_t k) {
  static const std::vector<std::string> kPalette{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                                 "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                                 "#bcbd22", "#17becf"};
  return kPalette[k % kPalette.size()];
}

}  // namespace drapelab::report
