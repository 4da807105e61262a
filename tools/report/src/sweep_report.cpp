// The page for a sweep folder: the sweep table, and for each varied key the final metrics of
// interest against that key, one line per solver (and per value of the other varied keys).
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "drapelab/report/html_page.hpp"
#include "drapelab/report/report.hpp"
#include "drapelab/report/svg_plot.hpp"
#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"

namespace drapelab::report {

namespace fs = std::filesystem;
using nlohmann::json;
// The run folder's files, read through the one module that owns their formats.
using run_folder::CsvTable;
using run_folder::parse_csv;
using run_folder::parse_number;
using run_folder::read_csv_file;
using run_folder::read_file_bytes;

namespace {

constexpr double kLogSpan = 20.0;  // a log x axis when max / min of a positive key exceeds this

struct MetricSpec {
  std::string name;      // metric as the runner names it (summary.json final / top-level)
  std::string title;     // plot title
  std::string y_title;   // with units
  double scale;          // from the CSV's SI unit to the axis unit
  bool only_if_present;  // skip silently when the sweep has no value (drape needs a support)
};

const std::vector<MetricSpec>& metrics_of_interest() {
  static const std::vector<MetricSpec> specs{
      {"drape_coefficient", "Drape coefficient", "drape coefficient (1)", 1.0, true},
      {"max_stretch", "Max stretch", "max stretch (%)", 100.0, false},
      {"max_penetration", "Max penetration", "max penetration (mm)", 1e3, false},
      {"settle_time", "Settle time", "settle time (s)", 1.0, false},
      {"wall_seconds_per_simulated_second", "Cost", "cost (wall s per simulated s)", 1.0, false}};
  return specs;
}

// Columns that are never varied keys: the solver, its outcome and its measurements.
bool is_result_column(const std::string& name) {
  static const std::set<std::string> kResults{"solver",      "type",
                                              "integrator",  "status",
                                              "message",     "dt",
                                              "steps",       "exit_code",
                                              "ms_per_step", "wall_seconds",
                                              "run_folder",  "wall_seconds_per_simulated_second",
                                              "settle_time", "rest_jitter",
                                              "out",         "folder",
                                              "run_dir",     "run",
                                              "combination", "index",
                                              "case",        "id"};
  return kResults.count(name) > 0;
}

// A final metric's name (sweep.json may list the columns it wrote: they are not varied keys).
bool is_metric(const std::string& name) {
  static const std::set<std::string> kMetrics{
      "kinetic_energy",      "gravity_energy",    "spring_energy",   "max_stretch",
      "mean_stretch",        "min_clearance",     "max_penetration", "contact_count",
      "centroid_x",          "centroid_y",        "centroid_z",      "lowest_y",
      "projected_area",      "drape_coefficient", "drape_nodes",     "self_intersections",
      "triangle_penetration"};
  if (kMetrics.count(name)) return true;
  for (const std::string prefix : {"final.", "final_"})
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}

// A metric's column: its own name, or a prefixed form ("final.max_stretch", "final_max_stretch").
std::optional<std::size_t> metric_column(const CsvTable& table, const std::string& metric) {
  if (auto exact = table.column(metric)) return exact;
  for (std::size_t k = 0; k < table.header.size(); ++k) {
    const std::string& h = table.header[k];
    if (h == "final_" + metric ||
        (h.size() > metric.size() + 1 &&
         h.compare(h.size() - metric.size() - 1, std::string::npos, "." + metric) == 0))
      return k;
  }
  return std::nullopt;
}

// Every string in a JSON document, keys included.
void collect_strings(const json& j, std::set<std::string>& out) {
  if (j.is_string()) {
    out.insert(j.get<std::string>());
  } else if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      out.insert(key);
      collect_strings(value, out);
    }
  } else if (j.is_array()) {
    for (const auto& value : j) collect_strings(value, out);
  }
}

// The varied keys: the sweep.csv columns that sweep.json names; without sweep.json (or when it
// names none), the columns before "solver" that are not an index.
std::vector<std::string> varied_keys(const CsvTable& table, const json& sweep) {
  // drapelab sweep writes "varied": [{"key": ..., "values": [...]}, ...]: take those first.
  std::vector<std::string> listed;
  if (sweep.is_object() && sweep.contains("varied") && sweep["varied"].is_array())
    for (const auto& entry : sweep["varied"])
      if (entry.is_object() && entry.contains("key") && entry["key"].is_string() &&
          table.column(entry["key"].get<std::string>()))
        listed.push_back(entry["key"].get<std::string>());
  if (!listed.empty()) return listed;
  std::set<std::string> named;
  collect_strings(sweep, named);
  std::vector<std::string> keys;
  for (const auto& h : table.header)
    if (named.count(h) && !is_result_column(h) && !is_metric(h)) keys.push_back(h);
  if (!keys.empty()) return keys;
  for (const auto& h : table.header) {
    if (h == "solver") break;
    if (!is_result_column(h) && !is_metric(h)) keys.push_back(h);
  }
  return keys;
}

std::string short_key(const std::string& key) {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

struct SweepData {
  CsvTable table;
  json sweep;                        // sweep.json, or null
  std::vector<std::string> keys;     // varied keys, in column order
  std::vector<std::string> solvers;  // in order of appearance
  std::optional<std::size_t> solver_column, status_column;
};

bool failed(const SweepData& d, std::size_t row) {
  return d.status_column && d.table.text(row, d.status_column) != "ok";
}

std::string dash_pattern(std::size_t k) {
  static const std::vector<std::string> kDashes{"", "7 3", "2 3", "10 3 2 3", "4 4", "12 4"};
  return kDashes[k % kDashes.size()];
}

// The plots of every metric of interest against `key`.
std::string key_section(const SweepData& d, const std::string& key) {
  const CsvTable& t = d.table;
  const auto key_column = t.column(key);
  // Numeric when every non-empty value is a number; otherwise categories in order of appearance.
  bool numeric = true;
  std::vector<std::string> categories;
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const std::string& cell = t.text(r, key_column);
    if (std::find(categories.begin(), categories.end(), cell) == categories.end())
      categories.push_back(cell);
    const auto value = parse_number(cell);
    if (!value || !std::isfinite(*value)) {
      numeric = false;
    } else {
      x_min = std::min(x_min, *value);
      x_max = std::max(x_max, *value);
    }
  }
  const bool log_x = numeric && x_min > 0.0 && x_max / x_min > kLogSpan;
  auto x_of = [&](std::size_t r) {
    const std::string& cell = t.text(r, key_column);
    if (numeric) return *parse_number(cell);
    return static_cast<double>(std::find(categories.begin(), categories.end(), cell) -
                               categories.begin());
  };

  // Lines: one per solver and combination of the other varied keys' values.
  std::vector<std::size_t> other_columns;
  for (const auto& other : d.keys)
    if (other != key) other_columns.push_back(*t.column(other));
  std::vector<std::string>
      other_labels;  // "ks=100, kd=0.1" per combination, in order of appearance
  std::map<std::pair<std::string, std::string>, std::vector<std::size_t>> line_rows;
  std::vector<std::pair<std::string, std::string>> line_order;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    std::string others;
    for (const std::size_t c : other_columns)
      others += (others.empty() ? "" : ", ") + short_key(t.header[c]) + "=" + t.text(r, c);
    if (std::find(other_labels.begin(), other_labels.end(), others) == other_labels.end())
      other_labels.push_back(others);
    const std::pair<std::string, std::string> line{t.text(r, d.solver_column), others};
    auto [it, inserted] = line_rows.try_emplace(line);
    if (inserted) line_order.push_back(line);
    it->second.push_back(r);
  }

  std::string html =
      "<h2 id=\"key-" + escape_xml(key) + "\">Against " + escape_xml(key) + "</h2>\n";
  html += "<p class=\"note\">" +
          std::string(log_x ? "Logarithmic x axis (the values span more than a factor 20). " : "") +
          "One colour per solver; " +
          (other_columns.empty()
               ? std::string("")
               : std::string("one dash pattern per value of the other varied keys; ")) +
          "a cross marks a run whose status is not ok (on the x axis when it has no value).</p>\n";
  html += "<div class=\"plots\">\n";
  std::vector<std::string> skipped;
  for (const auto& metric : metrics_of_interest()) {
    const auto column = metric_column(t, metric.name);
    bool present = false;
    if (column)
      for (std::size_t r = 0; r < t.rows.size() && !present; ++r)
        present = std::isfinite(t.number(r, column));
    if (!present) {
      if (!metric.only_if_present) skipped.push_back(metric.name);
      continue;
    }
    Plot plot;
    plot.title = metric.title + " against " + short_key(key);
    plot.x_title = key;
    plot.y_title = metric.y_title;
    plot.log_x = log_x;
    if (!numeric) plot.x_categories = categories;
    for (const auto& line : line_order) {
      std::vector<std::size_t> rows = line_rows.at(line);
      std::stable_sort(rows.begin(), rows.end(),
                       [&](std::size_t a, std::size_t b) { return x_of(a) < x_of(b); });
      Series s;
      const auto solver_index = static_cast<std::size_t>(
          std::find(d.solvers.begin(), d.solvers.end(), line.first) - d.solvers.begin());
      // A row without a solver is a run that gave no per-solver result (it failed before).
      s.label = (line.first.empty() ? std::string("(no solver)") : line.first) +
                (line.second.empty() ? "" : " (" + line.second + ")");
      s.color = palette_color(solver_index);
      s.dash = dash_pattern(static_cast<std::size_t>(
          std::find(other_labels.begin(), other_labels.end(), line.second) - other_labels.begin()));
      s.point_markers = true;
      for (const std::size_t r : rows) {
        s.x.push_back(x_of(r));
        s.y.push_back(metric.scale * t.number(r, column));
        s.failed.push_back(failed(d, r));
      }
      plot.series.push_back(std::move(s));
    }
    html += "<figure>\n" + svg_plot(plot) + "<figcaption>sweep.csv " +
            escape_xml(t.header[*column]) + " at the end of each run</figcaption>\n</figure>\n";
  }
  html += "</div>\n";
  if (!skipped.empty()) {
    std::string list;
    for (const auto& name : skipped) list += (list.empty() ? "" : ", ") + name;
    html += "<p class=\"note\">Not in sweep.csv (no column or no value): " + escape_xml(list) +
            ".</p>\n";
  }
  return html;
}

std::string table_section(const SweepData& d) {
  const CsvTable& t = d.table;
  std::vector<std::vector<TableCell>> rows;
  std::set<std::size_t> key_columns;
  for (const auto& key : d.keys) key_columns.insert(*t.column(key));
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    std::vector<TableCell> row;
    for (std::size_t c = 0; c < t.header.size(); ++c) {
      const std::string& cell = t.rows[r][c];
      if (d.solver_column && c == *d.solver_column) {
        const auto index = static_cast<std::size_t>(
            std::find(d.solvers.begin(), d.solvers.end(), cell) - d.solvers.begin());
        row.push_back({color_swatch(palette_color(index)) + escape_xml(cell), false});
      } else if (d.status_column && c == *d.status_column) {
        row.push_back({"<span class=\"" + std::string(cell == "ok" ? "status-ok" : "status-bad") +
                           "\">" + escape_xml(cell) + "</span>",
                       false});
      } else if (t.header[c] == "message") {
        row.push_back({escape_xml(cell), false, true});
      } else if (const auto value = parse_number(cell); value && !key_columns.count(c)) {
        row.push_back(
            {format_value(*value), true});  // measurements to 4 digits; varied values as given
      } else {
        row.push_back(
            {escape_xml(cell), key_columns.count(c) > 0 && parse_number(cell).has_value()});
      }
    }
    rows.push_back(std::move(row));
  }
  return "<h2 id=\"table\">Sweep table</h2>\n" + html_table(t.header, rows);
}

}  // namespace

std::string sweep_report_html(const fs::path& folder) {
  SweepData d;
  const auto csv_text = read_file_bytes(folder / "sweep.csv");
  if (!csv_text) throw std::runtime_error("cannot read " + (folder / "sweep.csv").string());
  d.table = parse_csv(*csv_text);
  d.solver_column = d.table.column("solver");
  d.status_column = d.table.column("status");
  if (!d.solver_column)
    throw std::runtime_error((folder / "sweep.csv").string() + " has no solver column");
  if (const auto json_text = read_file_bytes(folder / "sweep.json")) {
    try {
      d.sweep = json::parse(*json_text);
    } catch (const std::exception& e) {
      throw std::runtime_error((folder / "sweep.json").string() +
                               " is not valid JSON: " + e.what());
    }
  }
  d.keys = varied_keys(d.table, d.sweep);
  for (std::size_t r = 0; r < d.table.rows.size(); ++r) {
    const std::string& solver = d.table.text(r, d.solver_column);
    if (std::find(d.solvers.begin(), d.solvers.end(), solver) == d.solvers.end())
      d.solvers.push_back(solver);
  }

  std::size_t failures = 0;
  for (std::size_t r = 0; r < d.table.rows.size(); ++r) failures += failed(d, r) ? 1 : 0;
  std::string title = "sweep of " + folder.filename().string();
  if (d.sweep.is_object() && d.sweep.contains("scene") && d.sweep["scene"].is_string())
    title = "sweep of " + d.sweep["scene"].get<std::string>();
  std::string html = page_begin("drapelab report: " + title);
  html += "<h1>" + escape_xml(title) + "</h1>\n<p>";
  if (d.sweep.is_object() && d.sweep.contains("command") && d.sweep["command"].is_string())
    html += "Command: <code>" + escape_xml(d.sweep["command"].get<std::string>()) + "</code>. ";
  std::string key_list;
  for (const auto& key : d.keys)
    key_list += (key_list.empty() ? "" : ", ") + ("<code>" + escape_xml(key) + "</code>");
  html += "Sweep folder <code>" + escape_xml(folder.string()) +
          "</code>: " + std::to_string(d.table.rows.size()) +
          " row(s) (one per combination and solver), " + std::to_string(failures) +
          " not ok; varied: " + (key_list.empty() ? std::string("none found") : key_list) +
          ".</p>\n";
  html += table_section(d);
  for (const auto& key : d.keys) html += key_section(d, key);
  if (d.keys.empty())
    html +=
        "<p class=\"note\">No varied key found in sweep.csv (neither named in sweep.json nor a "
        "column before "
        "solver), so there is nothing to plot against.</p>\n";
  return html + page_end();
}

}  // namespace drapelab::report
