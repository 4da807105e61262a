// Line plots as inline SVG, drawn from our own code: axes with ticks and tick labels, axis titles,
// a legend, lines broken at missing values, and markers for failed runs and solvers that stopped
// early. The SVG needs no script and no external file.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace drapelab::report {

struct Series {
  std::string label;           // legend text
  std::string color;           // CSS colour, e.g. "#1f77b4"
  std::string dash;            // stroke-dasharray ("6 3"), empty for a solid line
  std::vector<double> x, y;    // equal lengths; a NaN in either breaks the line there
  std::vector<bool> failed;    // empty, or one per point: true draws a cross (a failed run)
  bool stopped_early = false;  // mark the last drawn point: the solver stopped before the end
  bool point_markers = false;  // a dot at every point (for plots of a few points, like sweeps)
};

struct Plot {
  std::string title;
  std::string x_title, y_title;           // axis titles, with units
  bool log_x = false;                     // decades on x (every x must be > 0; others are skipped)
  std::vector<std::string> x_categories;  // when given: x holds indices 0..n-1, labelled with these
  std::vector<Series> series;
};

// The plot as an <svg> element for an HTML page; `standalone` adds the XML namespace (and
// declaration) a .svg file needs to open on its own.
std::string svg_plot(const Plot& plot, bool standalone = false);

// Text for HTML or SVG: & < > " escaped.
std::string escape_xml(const std::string& text);

// The k-th colour of the report's palette (Tableau 10, chosen to stay distinct for colour-blind
// readers); it wraps after 10.
const std::string& palette_color(std::size_t k);

}  // namespace drapelab::report
