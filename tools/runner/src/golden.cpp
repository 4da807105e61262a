// Golden regression files (see golden.hpp).
#include "drapelab/runner/golden.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <system_error>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"
#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// Adds every row of one CSV table; `key_columns` name the row (joined by '/'). A table with its
// header alone (compare.csv of a scene with one solver, contacts.csv of one without colliders)
// adds nothing, and so does an absent one.
void read_table(const fs::path& path, const std::vector<std::string>& key_columns,
                std::map<int, GoldenRows>& out) {
  if (!fs::exists(path)) return;
  const auto text = run_folder::read_file_bytes(path);
  if (!text) throw std::runtime_error("cannot read " + path.string());
  const run_folder::CsvTable table = run_folder::parse_csv(*text);
  const std::vector<std::string>& header = table.header;
  const std::set<std::string> skipped = {"solver",   "frame",    "time",
                                         "collider", "solver_a", "solver_b"};
  const auto frame_column = table.column("frame");
  if (!frame_column) throw std::runtime_error(path.string() + " has no frame column");
  std::vector<std::size_t> keys;
  for (const auto& key : key_columns)
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == key) keys.push_back(c);
  for (const auto& cells : table.rows) {
    const auto frame = run_folder::parse_number(cells[*frame_column]);
    if (!frame) throw std::runtime_error(path.string() + " has a row without a frame number");
    std::string row;
    for (std::size_t k : keys) row += (row.empty() ? "" : "/") + cells[k];
    for (std::size_t c = 0; c < header.size(); ++c)
      if (!skipped.count(header[c]))
        out[static_cast<int>(*frame)][row][header[c]] = run_folder::parse_number(cells[c]);
  }
}

// The smallest scale of each kind, in the column's unit: below it a value is rounding noise, not
// physics (a strain of 1e-14 on a cloth at rest, a centroid_z of 1e-19 m on a symmetric drape).
double kind_floor(const std::string& kind) {
  if (kind == "position") return 1e-4;              // m: a tenth of a millimetre
  if (kind == "energy") return 1e-9;                // J
  if (kind == "strain") return 1e-4;                // 0.01 %
  if (kind == "penetration") return 1e-7;           // m
  if (kind == "clearance") return 1e-7;             // m
  if (kind == "force") return 1e-6;                 // N
  if (kind == "count") return 1.0;                  // one particle or node
  if (kind == "area") return 1e-6;                  // m^2
  if (kind == "distance") return 1e-6;              // m
  if (kind == "drape") return 1.0;                  // the drape coefficient is a fraction of 1
  if (kind == "intersections") return 1.0;          // one crossing edge
  if (kind == "triangle_penetration") return 1e-7;  // m
  if (kind == "constraint_error") return 1e-6;      // a relative length error
  return 1e-12;
}

std::string solver_of(const std::string& row) { return row.substr(0, row.find('/')); }

// Largest |value| of `column` over every frame, in the rows `take` accepts.
template <typename RowFilter>
double largest(const std::map<int, GoldenRows>& frames, const std::string& column, RowFilter take) {
  double biggest = 0.0;
  for (const auto& [frame, rows] : frames)
    for (const auto& [row, columns] : rows) {
      if (!take(row)) continue;
      const auto c = columns.find(column);
      if (c != columns.end() && c->second && std::isfinite(*c->second))
        biggest = std::max(biggest, std::abs(*c->second));
    }
  return biggest;
}

std::optional<double> value_at(const GoldenRows& rows, const std::string& row,
                               const std::string& column) {
  const auto r = rows.find(row);
  if (r == rows.end()) return std::nullopt;
  const auto c = r->second.find(column);
  if (c == r->second.end()) return std::nullopt;
  return c->second;
}

// The largest distance a solver's cloth moves from frame 0: its centroid (a vector) or its lowest
// point (m).
double motion_scale(const std::map<int, GoldenRows>& frames, const std::string& solver) {
  if (frames.empty()) return 0.0;
  const GoldenRows& first = frames.begin()->second;
  double biggest = 0.0;
  for (const auto& [frame, rows] : frames) {
    double squared = 0.0;
    for (const char* axis : {"centroid_x", "centroid_y", "centroid_z"}) {
      const auto now = value_at(rows, solver, axis), then = value_at(first, solver, axis);
      if (now && then && std::isfinite(*now - *then)) squared += (*now - *then) * (*now - *then);
    }
    biggest = std::max(biggest, std::sqrt(squared));
    const auto low = value_at(rows, solver, "lowest_y"), low0 = value_at(first, solver, "lowest_y");
    if (low && low0 && std::isfinite(*low - *low0))
      biggest = std::max(biggest, std::abs(*low - *low0));
  }
  return biggest;
}

// The most energy a solver's cloth has in motion or in its springs, or has released by falling (J).
double energy_scale(const std::map<int, GoldenRows>& frames, const std::string& solver) {
  if (frames.empty()) return 0.0;
  const auto start = value_at(frames.begin()->second, solver, "gravity_energy");
  double biggest = 0.0;
  for (const auto& [frame, rows] : frames) {
    const auto gravity = value_at(rows, solver, "gravity_energy");
    if (gravity && start && std::isfinite(*gravity - *start))
      biggest = std::max(biggest, std::abs(*gravity - *start));
  }
  auto same_solver = [&](const std::string& row) { return row == solver; };
  return std::max({biggest, largest(frames, "kinetic_energy", same_solver),
                   largest(frames, "spring_energy", same_solver)});
}

double scale_of(const std::map<int, GoldenRows>& frames, const std::string& row,
                const std::string& column) {
  const std::string kind = golden_kind(column);
  const std::string solver = solver_of(row);
  auto this_row = [&](const std::string& r) { return r == row; };
  auto solver_rows = [&](const std::string& r) { return solver_of(r) == solver; };
  double scale = 0.0;
  if (kind == "position")
    scale = motion_scale(frames, solver);
  else if (kind == "energy")
    scale = energy_scale(frames, solver);
  else if (kind == "strain")
    scale = largest(frames, "max_stretch", solver_rows);
  else if (kind == "penetration")
    scale = largest(frames, "max_penetration", solver_rows);
  else if (kind == "clearance")
    scale = largest(frames, column, this_row);
  else if (kind == "force")
    scale = largest(frames, "normal_force", solver_rows);
  else if (kind == "count")
    scale = column == "contact_count" ? largest(frames, column, solver_rows)
                                      : largest(frames, column, this_row);
  else if (kind == "distance")
    scale = std::max({largest(frames, "rms_distance", this_row),
                      largest(frames, "max_distance", this_row),
                      largest(frames, "hausdorff_distance", this_row)});
  else if (kind != "drape")
    scale = largest(frames, column, this_row);
  return std::max(scale, kind_floor(kind));
}

ordered_json value_json(std::optional<double> value) {
  return value && std::isfinite(*value) ? ordered_json(*value) : ordered_json();
}

ordered_json numbers_json(const GoldenNumbers& numbers) {
  ordered_json j = ordered_json::object();
  for (const auto& [row, columns] : numbers) {
    ordered_json row_json = ordered_json::object();
    for (const auto& [column, value] : columns) row_json[column] = value;
    j[row] = row_json;
  }
  return j;
}

GoldenNumbers numbers_from_json(const nlohmann::json& j) {
  GoldenNumbers numbers;
  for (const auto& [row, columns] : j.items())
    for (const auto& [column, value] : columns.items()) numbers[row][column] = value.get<double>();
  return numbers;
}

}  // namespace

std::optional<double> Golden::tolerance(const std::string& row, const std::string& column) const {
  const auto s = scale.find(row), r = relative.find(row);
  if (s == scale.end() || r == relative.end()) return std::nullopt;
  const auto sc = s->second.find(column), rc = r->second.find(column);
  if (sc == s->second.end() || rc == r->second.end()) return std::nullopt;
  return sc->second * rc->second;
}

std::size_t Golden::value_count() const {
  std::size_t count = 0;
  for (const auto& [frame, rows] : windows)
    for (const auto& [row, columns] : rows) count += columns.size();
  return count;
}

std::map<int, GoldenRows> read_run_values(const fs::path& run_dir) {
  std::map<int, GoldenRows> values;
  read_table(run_dir / "metrics.csv", {"solver"}, values);
  read_table(run_dir / "contacts.csv", {"solver", "collider"}, values);
  read_table(run_dir / "compare.csv", {"solver_a", "solver_b"}, values);
  return values;
}

std::vector<int> golden_window_ends(int frame_count, int windows) {
  std::set<int> ends{0};
  for (int k = 1; k <= windows; ++k)
    ends.insert(std::max(1, static_cast<int>(static_cast<long long>(frame_count) * k / windows)));
  if (frame_count <= 0) ends = {0};
  return {ends.begin(), ends.end()};
}

std::map<int, GoldenRows> window_means(const std::map<int, GoldenRows>& frames,
                                       const std::vector<int>& ends) {
  std::map<int, GoldenRows> means;
  int first = ends.empty() ? 0 : ends.front();
  for (const int end : ends) {
    std::map<std::pair<std::string, std::string>, std::pair<double, int>> sums;  // sum, count
    for (auto f = frames.lower_bound(first); f != frames.end() && f->first <= end; ++f)
      for (const auto& [row, columns] : f->second)
        for (const auto& [column, value] : columns) {
          auto& [sum, count] = sums[{row, column}];
          if (value && std::isfinite(*value)) {
            sum += *value;
            ++count;
          }
        }
    GoldenRows& window = means[end];
    for (const auto& [cell, total] : sums)
      window[cell.first][cell.second] =
          total.second > 0 ? std::optional<double>(total.first / total.second) : std::nullopt;
    first = end + 1;
  }
  return means;
}

std::string golden_kind(const std::string& column) {
  if (column == "centroid_x" || column == "centroid_y" || column == "centroid_z" ||
      column == "lowest_y")
    return "position";
  if (column == "kinetic_energy" || column == "gravity_energy" || column == "spring_energy" ||
      column == "elastic_energy" || column == "contact_energy" || column == "constraint_energy" ||
      column == "total_energy")
    return "energy";
  if (column == "max_stretch" || column == "mean_stretch") return "strain";
  if (column == "max_penetration") return "penetration";
  if (column == "min_clearance") return "clearance";
  if (column == "normal_force" || column == "friction_force") return "force";
  if (column == "contact_count" || column == "drape_nodes") return "count";
  if (column == "projected_area") return "area";
  if (column == "rms_distance" || column == "max_distance" || column == "hausdorff_distance")
    return "distance";
  if (column == "drape_coefficient") return "drape";
  // Kinds of their own, scaled by their own largest value: a fold's crossings or a collider's reach
  // between particles must not widen the tolerances of the contact columns they would pool with.
  if (column == "self_intersections") return "intersections";
  if (column == "triangle_penetration") return "triangle_penetration";
  if (column == "constraint_error") return "constraint_error";
  return "other";
}

GoldenNumbers golden_scales(const std::map<int, GoldenRows>& frames) {
  GoldenNumbers scales;
  for (const auto& [frame, rows] : frames)
    for (const auto& [row, columns] : rows)
      for (const auto& [column, value] : columns)
        if (!scales[row].count(column)) scales[row][column] = scale_of(frames, row, column);
  return scales;
}

GoldenNumbers golden_relative(const GoldenRule& rule, const GoldenNumbers& scale,
                              const std::map<int, GoldenRows>& recorded,
                              const std::vector<std::map<int, GoldenRows>>& probes) {
  // The probe's largest change per solver and kind, relative to each quantity's scale. A value the
  // probe run lacks (or has where the recorded run has none) counts as a change of the whole scale.
  std::map<std::pair<std::string, std::string>, double> noise;
  for (const auto& probe : probes)
    for (const auto& [frame, rows] : recorded)
      for (const auto& [row, columns] : rows)
        for (const auto& [column, value] : columns) {
          const double s = scale.at(row).at(column);
          const auto p = probe.find(frame);
          const std::optional<std::optional<double>> other =
              p == probe.end()
                  ? std::nullopt
                  : std::optional<std::optional<double>>(value_at(p->second, row, column));
          double change = 0.0;
          const bool here = value.has_value(), there = other && other->has_value();
          if (here != there)
            change = 1.0;
          else if (here)
            change = std::abs(**other - *value) / s;
          if (!std::isfinite(change)) change = 1.0;
          auto& n = noise[{solver_of(row), golden_kind(column)}];
          n = std::max(n, change);
        }
  GoldenNumbers relative;
  for (const auto& [row, columns] : scale)
    for (const auto& [column, s] : columns) {
      const auto n = noise.find({solver_of(row), golden_kind(column)});
      const double measured = n == noise.end() ? 0.0 : rule.noise_factor * n->second;
      relative[row][column] = std::max(rule.relative_floor, measured);
    }
  return relative;
}

std::vector<GoldenDifference> compare_golden(const Golden& golden,
                                             const std::map<int, GoldenRows>& actual) {
  std::vector<GoldenDifference> differences;
  static const GoldenRows kNoRows;
  std::set<int> frames;
  for (const auto& [frame, rows] : golden.windows) frames.insert(frame);
  for (const auto& [frame, rows] : actual) frames.insert(frame);
  for (int frame : frames) {
    const auto expected_frame = golden.windows.find(frame);
    const auto actual_frame = actual.find(frame);
    const GoldenRows& expected_rows =
        expected_frame != golden.windows.end() ? expected_frame->second : kNoRows;
    const GoldenRows& actual_rows = actual_frame != actual.end() ? actual_frame->second : kNoRows;
    std::set<std::pair<std::string, std::string>> cells;
    for (const auto& [row, columns] : expected_rows)
      for (const auto& [column, value] : columns) cells.insert({row, column});
    for (const auto& [row, columns] : actual_rows)
      for (const auto& [column, value] : columns) cells.insert({row, column});
    for (const auto& cell : cells) {
      const std::string& row = cell.first;  // named, not bound: clang 14 cannot capture bindings
      const std::string& column = cell.second;
      auto lookup = [&](const GoldenRows& rows) -> std::optional<std::optional<double>> {
        const auto r = rows.find(row);
        if (r == rows.end()) return std::nullopt;
        const auto c = r->second.find(column);
        if (c == r->second.end()) return std::nullopt;
        return c->second;
      };
      const auto expected = lookup(expected_rows), found = lookup(actual_rows);
      const auto tolerance = golden.tolerance(row, column);
      GoldenDifference d{frame,
                         row,
                         column,
                         expected ? *expected : std::nullopt,
                         found ? *found : std::nullopt,
                         tolerance,
                         std::nullopt};
      if (const auto s = golden.scale.find(row); s != golden.scale.end())
        if (const auto c = s->second.find(column); c != s->second.end()) d.scale = c->second;
      // An empty cell and a cell the other side lacks are alike: a column added to the outputs,
      // empty for this scene (constraint_error without constraints), is no change.
      if (!d.expected && !d.actual) continue;
      if (d.expected && d.actual && std::abs(*d.actual - *d.expected) <= tolerance.value_or(0.0))
        continue;
      differences.push_back(d);
    }
  }
  return differences;
}

std::string describe_difference(const GoldenDifference& d) {
  auto text = [](std::optional<double> v) { return v ? format_number(*v) : std::string("(none)"); };
  std::string line = "frame " + std::to_string(d.frame) + " " + d.row + " " + d.column + ": " +
                     text(d.expected) + " -> " + text(d.actual);
  if (d.expected && d.actual && d.scale && *d.scale > 0.0) {
    char change[96];
    std::snprintf(change, sizeof change, " (%+.3g %% of its scale %.3g; tolerance %.3g %%)",
                  100.0 * (*d.actual - *d.expected) / *d.scale, *d.scale,
                  100.0 * d.tolerance.value_or(0.0) / *d.scale);
    line += change;
  }
  return line;
}

std::string golden_to_json(const Golden& golden) {
  ordered_json j;
  j["scene"] = golden.scene;
  j["overrides"] = golden.overrides;
  j["rule"] = {{"windows", golden.rule.windows},
               {"relative_floor", golden.rule.relative_floor},
               {"noise_factor", golden.rule.noise_factor},
               {"probe", golden.rule.probe}};
  j["scale"] = numbers_json(golden.scale);
  j["relative"] = numbers_json(golden.relative);
  ordered_json windows = ordered_json::object();
  for (const auto& [frame, rows] : golden.windows) {
    ordered_json frame_json = ordered_json::object();
    for (const auto& [row, columns] : rows) {
      ordered_json row_json = ordered_json::object();
      for (const auto& [column, value] : columns) row_json[column] = value_json(value);
      frame_json[row] = row_json;
    }
    windows[std::to_string(frame)] = frame_json;
  }
  j["windows"] = windows;
  // A path or command line that is not UTF-8 is written with U+FFFD, not refused.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::optional<Golden> golden_from_json(const std::string& text, std::string* error) {
  const auto j = nlohmann::json::parse(text, nullptr, false);
  auto fail = [&](const std::string& message) -> std::optional<Golden> {
    if (error) *error = message;
    return std::nullopt;
  };
  if (j.is_discarded() || !j.is_object()) return fail("is not valid JSON");
  Golden golden;
  try {
    golden.scene = j.at("scene").get<std::string>();
    golden.overrides = j.at("overrides").get<std::vector<std::string>>();
    const auto& rule = j.at("rule");
    golden.rule = {rule.at("windows").get<int>(), rule.at("relative_floor").get<double>(),
                   rule.at("noise_factor").get<double>(), rule.at("probe").get<double>()};
    golden.scale = numbers_from_json(j.at("scale"));
    golden.relative = numbers_from_json(j.at("relative"));
    for (const auto& [frame, rows] : j.at("windows").items()) {
      std::size_t used = 0;
      const int number = std::stoi(frame, &used);
      if (used != frame.size() || number < 0)
        return fail("has a window key '" + frame + "' that is not a frame number");
      GoldenRows& out = golden.windows[number];
      for (const auto& [row, columns] : rows.items())
        for (const auto& [column, value] : columns.items())
          out[row][column] =
              value.is_null() ? std::nullopt : std::optional<double>(value.get<double>());
    }
  } catch (const std::exception& e) {
    return fail(std::string("is not a drapelab golden file (") + e.what() +
                "; record it again with drapelab check --update)");
  }
  // A golden file that compares nothing would pass every run: refuse it.
  if (golden.value_count() == 0)
    return fail(
        "holds no values: a golden file that compares nothing checks nothing (record it "
        "again with drapelab check --update)");
  for (const auto& [frame, rows] : golden.windows)
    for (const auto& [row, columns] : rows)
      for (const auto& [column, value] : columns) {
        const auto tolerance = golden.tolerance(row, column);
        if (!tolerance || !std::isfinite(*tolerance) || *tolerance < 0.0)
          return fail("has no valid tolerance for " + row + " " + column +
                      " (its scale and relative entries)");
      }
  return golden;
}

std::optional<std::string> write_golden_file(const fs::path& path, const std::string& text) {
  const fs::path temporary =
      path.parent_path() / (path.filename().string() + ".partial-" + std::to_string(::getpid()));
  std::error_code ec;
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.flush();
    if (!file) {
      fs::remove(temporary, ec);
      return "cannot write " + temporary.string() + " (is its folder writable?)";
    }
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    const std::string message = "cannot replace " + path.string() + ": " + ec.message();
    fs::remove(temporary, ec);
    return message;
  }
  return std::nullopt;
}

}  // namespace drapelab::runner
