// The page for a run folder: the scene, the last rendered frame and the video when there are any,
// the solvers' summary, and the per-frame metrics of every solver on shared axes.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <system_error>

#include "drapelab/report/html_page.hpp"
#include "drapelab/report/report.hpp"
#include "drapelab/report/run_completeness.hpp"
#include "drapelab/report/svg_plot.hpp"
#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"

namespace drapelab::report {

namespace fs = std::filesystem;
using nlohmann::ordered_json;
// The run folder's files, read through the one module that owns their formats.
using run_folder::CsvTable;
using run_folder::parse_csv;
using run_folder::parse_number;
using run_folder::read_file_bytes;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct RunData {
  fs::path folder;
  ordered_json summary;
  std::string scene_text;   // scene.yaml as given
  std::string description;  // from scene.yaml, may be empty
  CsvTable metrics, compare, contacts;
  std::vector<std::string> solvers;           // summary.json's order, then any only in metrics.csv
  std::map<std::string, std::string> colors;  // solver -> colour, the same in every plot and table
};

std::string read_required(const fs::path& path) {
  auto text = read_file_bytes(path);
  if (!text) throw std::runtime_error("cannot read " + path.string());
  return *text;
}

RunData load_run(const fs::path& folder) {
  RunData run;
  run.folder = folder;
  const std::string summary_text = read_required(folder / "summary.json");
  try {
    run.summary = ordered_json::parse(summary_text);
  } catch (const std::exception& e) {
    throw std::runtime_error((folder / "summary.json").string() +
                             " is not valid JSON: " + e.what());
  }
  run.scene_text = read_required(folder / "scene.yaml");
  try {
    const YAML::Node scene = YAML::Load(run.scene_text);
    if (scene["description"] && scene["description"].IsScalar())
      run.description = scene["description"].as<std::string>();
  } catch (const std::exception&) {
    // The description is only shown; a scene.yaml that does not parse is still shown as text.
  }
  // A CSV whose writer was killed may end in half a row: it is left out (run_completeness.hpp says
  // so on the page).
  run.metrics = parse_csv(whole_rows(read_required(folder / "metrics.csv"), nullptr));
  if (!run.metrics.column("solver") || !run.metrics.column("time"))
    throw std::runtime_error((folder / "metrics.csv").string() + " has no solver and time columns");
  if (auto text = read_file_bytes(folder / "compare.csv"))
    run.compare = parse_csv(whole_rows(*text, nullptr));
  if (auto text = read_file_bytes(folder / "contacts.csv"))
    run.contacts = parse_csv(whole_rows(*text, nullptr));

  if (run.summary.contains("solvers") && run.summary["solvers"].is_object())
    for (const auto& [name, value] : run.summary["solvers"].items()) run.solvers.push_back(name);
  const auto solver_column = run.metrics.column("solver");
  for (std::size_t r = 0; r < run.metrics.rows.size(); ++r) {
    const std::string& name = run.metrics.text(r, solver_column);
    if (std::find(run.solvers.begin(), run.solvers.end(), name) == run.solvers.end())
      run.solvers.push_back(name);
  }
  for (std::size_t k = 0; k < run.solvers.size(); ++k)
    run.colors[run.solvers[k]] = palette_color(k);
  return run;
}

// summary.json's object for one solver (null when absent).
const ordered_json& solver_summary(const RunData& run, const std::string& solver) {
  static const ordered_json null_json;
  if (!run.summary.contains("solvers") || !run.summary["solvers"].contains(solver))
    return null_json;
  return run.summary["solvers"][solver];
}

std::string json_text(const ordered_json& j, const std::string& key) {
  if (!j.is_object() || !j.contains(key) || j[key].is_null()) return "";
  return j[key].is_string() ? j[key].get<std::string>() : j[key].dump();
}

double json_number(const ordered_json& j, const std::string& key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return kNaN;
  return j[key].get<double>();
}

bool stopped_early(const RunData& run, const std::string& solver) {
  const std::string status = json_text(solver_summary(run, solver), "status");
  return !status.empty() && status != "ok";
}

// One series per solver of a metrics.csv column, times `scale` (unit change).
std::vector<Series> metric_series(const RunData& run, const std::string& column, double scale) {
  const auto solver_column = run.metrics.column("solver");
  const auto time_column = run.metrics.column("time");
  const auto value_column = run.metrics.column(column);
  std::vector<Series> series;
  for (const auto& solver : run.solvers) {
    Series s;
    s.label = solver;
    s.color = run.colors.at(solver);
    s.stopped_early = stopped_early(run, solver);
    for (std::size_t r = 0; r < run.metrics.rows.size(); ++r) {
      if (run.metrics.text(r, solver_column) != solver) continue;
      s.x.push_back(run.metrics.number(r, time_column));
      s.y.push_back(scale * run.metrics.number(r, value_column));
    }
    series.push_back(std::move(s));
  }
  return series;
}

bool any_finite(const std::vector<Series>& series) {
  for (const auto& s : series)
    for (const double y : s.y)
      if (std::isfinite(y)) return true;
  return false;
}

// Sum over colliders of contacts.csv's normal_force, per solver and frame (N).
std::vector<Series> contact_force_series(const RunData& run) {
  const CsvTable& t = run.contacts;
  const auto solver_column = t.column("solver"), frame_column = t.column("frame"),
             time_column = t.column("time"), force_column = t.column("normal_force");
  std::vector<Series> series;
  if (!solver_column || !frame_column || !force_column) return series;
  for (const auto& solver : run.solvers) {
    std::map<long, std::pair<double, double>> by_frame;  // frame -> (time, summed force)
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      if (t.text(r, solver_column) != solver) continue;
      const auto frame = parse_number(t.text(r, frame_column));
      if (!frame) continue;
      auto [it, inserted] =
          by_frame.try_emplace(static_cast<long>(*frame), t.number(r, time_column), 0.0);
      it->second.second +=
          t.number(r, force_column);  // a NaN cell makes the frame's sum NaN: a gap
    }
    Series s;
    s.label = solver;
    s.color = run.colors.at(solver);
    s.stopped_early = stopped_early(run, solver);
    for (const auto& [frame, value] : by_frame) {
      s.x.push_back(value.first);
      s.y.push_back(value.second);
    }
    series.push_back(std::move(s));
  }
  return series;
}

// compare.csv's rms_distance, one line per solver pair (mm).
std::vector<Series> distance_series(const RunData& run) {
  const CsvTable& t = run.compare;
  const auto a_column = t.column("solver_a"), b_column = t.column("solver_b"),
             time_column = t.column("time"), rms_column = t.column("rms_distance");
  std::vector<Series> series;
  if (!a_column || !b_column || !rms_column) return series;
  std::vector<std::pair<std::string, std::string>> pairs;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const std::pair<std::string, std::string> pair{t.text(r, a_column), t.text(r, b_column)};
    if (std::find(pairs.begin(), pairs.end(), pair) == pairs.end()) pairs.push_back(pair);
  }
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    Series s;
    s.label = pairs[k].first + " \u2013 " + pairs[k].second;
    // Pairs are not solvers: colours after the solvers' ones, dashed, so no pair looks like a
    // solver.
    s.color = palette_color(run.solvers.size() + k);
    s.dash = "7 3";
    s.stopped_early = stopped_early(run, pairs[k].first) || stopped_early(run, pairs[k].second);
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      if (t.text(r, a_column) != pairs[k].first || t.text(r, b_column) != pairs[k].second) continue;
      s.x.push_back(t.number(r, time_column));
      s.y.push_back(1e3 * t.number(r, rms_column));
    }
    series.push_back(std::move(s));
  }
  return series;
}

std::string figure(const Plot& plot, const std::string& caption) {
  return "<figure>\n" + svg_plot(plot) + "<figcaption>" + caption + "</figcaption>\n</figure>\n";
}

std::string plots_section(const RunData& run) {
  std::string html =
      "<h2 id=\"plots\">Metrics over time</h2>\n<p class=\"note\">Every solver on shared axes, "
      "one colour per solver in every plot and table. A square marks the last frame of a "
      "solver that stopped early; a gap is a frame with no value.</p>\n<div class=\"plots\">\n";
  const std::string time_title = "time (s)";
  auto add = [&](const std::string& title, const std::string& y_title, std::vector<Series> series,
                 const std::string& caption) {
    Plot plot;
    plot.title = title;
    plot.x_title = time_title;
    plot.y_title = y_title;
    plot.series = std::move(series);
    html += figure(plot, caption);
  };
  add("Kinetic energy", "kinetic energy (J)", metric_series(run, "kinetic_energy", 1.0),
      "metrics.csv kinetic_energy: \u03a3 \u00bd m v\u00b2");
  add("Spring energy", "spring energy (J)", metric_series(run, "spring_energy", 1.0),
      "metrics.csv spring_energy: every spring, with the model's stiffness");
  add("Max stretch", "max stretch (%)", metric_series(run, "max_stretch", 100.0),
      "metrics.csv max_stretch: largest |x_a \u2212 x_b| / L \u2212 1 over stretch springs");
  std::string notes;
  auto clearance = metric_series(run, "min_clearance", 1e3);
  if (any_finite(clearance)) {
    add("Min clearance", "min clearance (mm)", std::move(clearance),
        "metrics.csv min_clearance: signed distance to the nearest collider less the thickness; "
        "below 0 = "
        "inside the shell");
    add("Max penetration", "max penetration (mm)", metric_series(run, "max_penetration", 1e3),
        "metrics.csv max_penetration: max(0, \u2212min_clearance)");
    add("Triangle penetration", "triangle penetration (mm)",
        metric_series(run, "triangle_penetration", 1e3),
        "metrics.csv triangle_penetration: deepest reach of a collider into a triangle, "
        "thickness included: max(0, h \u2212 d) over triangles and colliders");
  } else {
    notes +=
        "<p class=\"note\">No clearance or penetration plots: the scene has no colliders.</p>\n";
  }
  auto crossings = metric_series(run, "self_intersections", 1.0);
  if (any_finite(crossings))
    add("Self-intersections", "crossing edges (1)", std::move(crossings),
        "metrics.csv self_intersections: cloth edges that cross a non-adjacent cloth triangle "
        "(exact predicates)");
  auto forces = contact_force_series(run);
  if (any_finite(forces))
    add("Contact force", "normal force, all colliders (N)", std::move(forces),
        "contacts.csv normal_force summed over colliders (magnitudes; 0 at frame 0)");
  else
    notes += "<p class=\"note\">No contact force plot: contacts.csv holds no rows.</p>\n";
  auto drape = metric_series(run, "drape_coefficient", 1.0);
  if (any_finite(drape))
    add("Drape coefficient", "drape coefficient (1)", std::move(drape),
        "metrics.csv drape_coefficient: Cusick (A_s \u2212 A_d) / (A_D \u2212 A_d)");
  auto distances = distance_series(run);
  if (!distances.empty())
    add("Distance between solvers", "rms distance (mm)", std::move(distances),
        "compare.csv rms_distance: vertex-area weighted, one line per solver pair");
  else
    notes += "<p class=\"note\">No distance plot: the run has a single solver.</p>\n";
  return html + "</div>\n" + notes;
}

std::string last_row_cell(const ordered_json& final_metrics, const std::string& key, double scale) {
  return format_value(scale * json_number(final_metrics, key));
}

// The energy audit's warnings (summary.json's energy_warnings), one line each under the table:
// in a passive scene a rise of the total energy is energy the method made (docs/metrics.md).
std::string energy_warning_notes(const RunData& run) {
  std::string html;
  for (const auto& solver : run.solvers) {
    const ordered_json& s = solver_summary(run, solver);
    if (!s.is_object() || !s.contains("energy_warnings") || !s["energy_warnings"].is_array())
      continue;
    for (const auto& w : s["energy_warnings"]) {
      if (!w.is_object()) continue;
      html += "<p class=\"status-bad\">Energy: " + escape_xml(solver) + " at frame " +
              format_value(json_number(w, "frame"), 10) +
              " (t = " + format_value(json_number(w, "time")) + " s): the total energy rose by " +
              format_value(json_number(w, "rise_J")) +
              " J in a passive scene; likely cause: " + escape_xml(json_text(w, "cause")) +
              "</p>\n";
    }
  }
  return html;
}

std::string summary_section(const RunData& run) {
  std::string html = "<h2 id=\"summary\">Solvers</h2>\n";
  std::vector<std::vector<TableCell>> rows, final_rows;
  for (const auto& solver : run.solvers) {
    const ordered_json& s = solver_summary(run, solver);
    const std::string status = json_text(s, "status");
    const std::string kind = json_text(s, "integrator").empty()
                                 ? json_text(s, "type")
                                 : json_text(s, "type") + " (" + json_text(s, "integrator") + ")";
    const TableCell name{color_swatch(run.colors.at(solver)) + escape_xml(solver), false};
    rows.push_back({name,
                    {escape_xml(kind), false},
                    {"<span class=\"" + std::string(status == "ok" ? "status-ok" : "status-bad") +
                         "\">" + escape_xml(status.empty() ? "\u2014" : status) + "</span>",
                     false},
                    {escape_xml(json_text(s, "message")), false, true},
                    {format_value(json_number(s, "dt")), true},
                    {format_value(json_number(s, "steps"), 10), true},
                    {format_value(json_number(s, "ms_per_step")), true},
                    {format_value(json_number(s, "wall_seconds_per_simulated_second")), true},
                    {format_value(json_number(s, "settle_time")), true},
                    {format_value(json_number(s, "rest_jitter")), true}});
    const ordered_json final_metrics =
        s.is_object() && s.contains("final") ? s["final"] : ordered_json();
    double centroid_y = kNaN;
    if (final_metrics.is_object() && final_metrics.contains("centroid") &&
        final_metrics["centroid"].is_array() && final_metrics["centroid"].size() == 3 &&
        final_metrics["centroid"][1].is_number())
      centroid_y = final_metrics["centroid"][1].get<double>();
    final_rows.push_back({name,
                          {last_row_cell(final_metrics, "kinetic_energy", 1.0), true},
                          {last_row_cell(final_metrics, "max_stretch", 100.0), true},
                          {last_row_cell(final_metrics, "mean_stretch", 100.0), true},
                          {last_row_cell(final_metrics, "min_clearance", 1e3), true},
                          {last_row_cell(final_metrics, "max_penetration", 1e3), true},
                          {last_row_cell(final_metrics, "contact_count", 1.0), true},
                          {format_value(centroid_y), true},
                          {last_row_cell(final_metrics, "lowest_y", 1.0), true},
                          {last_row_cell(final_metrics, "projected_area", 1.0), true},
                          {last_row_cell(final_metrics, "drape_coefficient", 1.0), true},
                          {last_row_cell(final_metrics, "drape_nodes", 1.0), true}});
  }
  html +=
      html_table({"solver", "type (integrator)", "status", "message", "dt (s)", "steps",
                  "ms per step", "wall s per simulated s", "settle time (s)", "rest jitter (m/s)"},
                 rows);
  html +=
      "<p class=\"note\">Cost is wall-clock time on the machine that made the run. Settle time: "
      "first "
      "time after which the kinetic energy stays below 1e-6 of the gravity energy released; rest "
      "jitter: RMS velocity over the last second (docs/metrics.md). An em dash: not "
      "measured.</p>\n";
  html += energy_warning_notes(run);
  html += "<h3>Final metrics</h3>\n";
  html +=
      html_table({"solver", "kinetic energy (J)", "max stretch (%)", "mean stretch (%)",
                  "min clearance (mm)", "max penetration (mm)", "contacts", "centroid y (m)",
                  "lowest y (m)", "projected area (m\u00b2)", "drape coefficient", "drape nodes"},
                 final_rows);
  return html;
}

// The render folder's frame_NNNN.png with the largest number, if any.
std::optional<fs::path> last_frame(const fs::path& render) {
  std::error_code ec;
  std::optional<fs::path> best;
  long best_number = -1;
  for (const auto& entry : fs::directory_iterator(render, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("frame_", 0) != 0 || entry.path().extension() != ".png") continue;
    const auto number = parse_number(name.substr(6, name.size() - 10));
    if (!number) continue;
    if (static_cast<long>(*number) > best_number) {
      best_number = static_cast<long>(*number);
      best = entry.path();
    }
  }
  return best;
}

std::string media_section(const RunData& run, const fs::path& report_file) {
  std::string html = "<h2 id=\"render\">Last frame</h2>\n";
  const fs::path render = run.folder / "render";
  std::error_code ec;
  const std::string command = "drapelab render " + run.folder.string();
  if (const auto frame = last_frame(render)) {
    const auto bytes = read_file_bytes(*frame);
    if (!bytes) throw std::runtime_error("cannot read " + frame->string());
    html +=
        "<figure>\n<img class=\"still\" alt=\"last rendered frame, every solver side by side\" "
        "src=\"data:image/png;base64," +
        base64_encode(*bytes) + "\"/>\n<figcaption>render/" +
        escape_xml(frame->filename().string()) +
        ", every solver side by side</figcaption>\n</figure>\n";
  } else if (fs::is_directory(run.folder / "meshes", ec)) {
    html += "<p>No rendered frames yet. Make them with <code>" + escape_xml(command) +
            "</code>, then write this report again.</p>\n";
  } else {
    // drapelab render draws from the run's point caches, which a run writes only when asked.
    html +=
        "<p>No rendered frames yet. The renderer draws from the run's meshes: run the scene again "
        "with "
        "<code>--meshes pc2</code>, then <code>" +
        escape_xml(command) + "</code>, then write this report again.</p>\n";
  }
  const fs::path video = render / "video.mp4";
  if (fs::is_regular_file(video, ec)) {
    // Relative to the page, so the page and the run folder can move together.
    const fs::path page_folder = fs::absolute(report_file).parent_path();
    const fs::path relative =
        fs::absolute(video).lexically_normal().lexically_relative(page_folder.lexically_normal());
    html +=
        "<h2 id=\"video\">Video</h2>\n<video controls=\"controls\" preload=\"metadata\" src=\"" +
        escape_xml(relative.generic_string()) + "\">render/video.mp4</video>\n";
  }
  return html;
}

// A notice at the top of the page when the run is not whole: killed, cut or interrupted.
std::string completeness_section(const RunCompleteness& completeness) {
  const auto notices = completeness.notices();
  if (notices.empty()) return "";
  std::string html = "<div class=\"" +
                     std::string(completeness.incomplete() ? "status-bad" : "note") +
                     "\" id=\"completeness\">\n<p>" +
                     (completeness.incomplete() ? "Incomplete run" : "Interrupted run") +
                     ": this page shows only the frames recorded.</p>\n<ul>\n";
  for (const auto& line : notices) html += "<li>" + escape_xml(line) + "</li>\n";
  return html + "</ul>\n</div>\n";
}

std::string scene_section(const RunData& run) {
  const ordered_json& s = run.summary;
  std::string html = "<h2 id=\"scene\">Scene</h2>\n";
  std::vector<std::vector<TableCell>> rows;
  auto row = [&](const std::string& key, const std::string& value) {
    if (!value.empty()) rows.push_back({{escape_xml(key), false}, {escape_xml(value), false}});
  };
  row("scene file", json_text(s, "scene_file"));
  row("command", json_text(s, "command"));
  row("drapelab version", json_text(s, "drapelab_version"));
  if (s.contains("run") && s["run"].is_object()) {
    const ordered_json& r = s["run"];
    row("run state", json_text(r, "state"));
    row("duration (s)", format_value(json_number(r, "duration"), 10));
    row("frame rate (1/s)", format_value(json_number(r, "frame_rate"), 10));
    row("frames done / planned", format_value(json_number(r, "frames_done"), 10) + " / " +
                                     format_value(json_number(r, "frames_planned"), 10));
  }
  if (s.contains("model") && s["model"].is_object()) {
    const ordered_json& m = s["model"];
    row("particles (pinned)", format_value(json_number(m, "particles"), 10) + " (" +
                                  format_value(json_number(m, "pinned"), 10) + ")");
    row("triangles", format_value(json_number(m, "triangles"), 10));
    row("total mass (kg)", format_value(json_number(m, "total_mass")));
  }
  html += html_table({"", ""}, rows);
  html += "<h3>scene.yaml</h3>\n<pre>" + escape_xml(run.scene_text) + "</pre>\n";
  return html;
}

}  // namespace

std::string run_report_html(const fs::path& folder, const fs::path& report_file) {
  const RunData run = load_run(folder);
  const std::string name = json_text(run.summary, "scene").empty()
                               ? folder.filename().string()
                               : json_text(run.summary, "scene");
  std::string html = page_begin("drapelab report: " + name);
  html += "<h1>" + escape_xml(name) + "</h1>\n";
  if (!run.description.empty()) html += "<p>" + escape_xml(run.description) + "</p>\n";
  html += "<p class=\"note\">Run folder <code>" + escape_xml(folder.string()) +
          "</code>: " + std::to_string(run.solvers.size()) +
          " solver(s). Sections: <a href=\"#render\">last frame</a>, "
          "<a href=\"#summary\">solvers</a>, <a href=\"#plots\">metrics over time</a>, <a "
          "href=\"#scene\">scene</a>.</p>\n";
  html += completeness_section(inspect_run(folder));
  html += media_section(run, report_file);
  html += summary_section(run);
  html += plots_section(run);
  html += scene_section(run);
  html +=
      "<p class=\"note\">Written by drapelab report from summary.json, metrics.csv, compare.csv "
      "and "
      "contacts.csv (docs/metrics.md defines every column).</p>\n";
  return html + page_end();
}

}  // namespace drapelab::report
