// Golden regression files (see golden.hpp).
#include "drapelab/runner/golden.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"
#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {
namespace {

using nlohmann::ordered_json;

// Adds the rows of one CSV table at the chosen frames; `key_columns` name the row (joined by '/').
void read_table(const std::filesystem::path& path, const std::vector<std::string>& key_columns,
                const std::set<int>& frames, std::map<int, GoldenRows>& out) {
  const run_folder::CsvTable table = run_folder::parse_csv(run_folder::read_file(path));
  const std::vector<std::string>& header = table.header;
  const std::set<std::string> skipped = {"solver",   "frame",    "time",
                                         "collider", "solver_a", "solver_b"};
  const auto frame_column = table.column("frame");
  if (!frame_column) return;
  std::vector<std::size_t> keys;
  for (std::size_t c = 0; c < header.size(); ++c)
    for (const auto& key : key_columns)
      if (header[c] == key) keys.push_back(c);
  for (const auto& cells : table.rows) {
    const int frame = std::stoi(cells[*frame_column]);
    if (!frames.count(frame)) continue;
    std::string row;
    for (std::size_t k : keys) row += (row.empty() ? "" : "/") + cells[k];
    for (std::size_t c = 0; c < header.size(); ++c)
      if (!skipped.count(header[c]))
        out[frame][row][header[c]] = run_folder::parse_number(cells[c]);
  }
}

bool is_count_column(const std::string& column) {
  return column == "contact_count" || column == "drape_nodes";
}

bool within(const GoldenTolerance& t, const std::string& column, std::optional<double> expected,
            std::optional<double> actual) {
  if (!expected || !actual) return expected.has_value() == actual.has_value();
  const double difference = std::abs(*actual - *expected);
  if (is_count_column(column)) return difference <= t.count;
  return difference <= t.absolute + t.relative * std::abs(*expected);
}

ordered_json value_json(std::optional<double> value) {
  return value ? ordered_json(*value) : ordered_json();
}

}  // namespace

std::vector<int> golden_frames(int frame_count) {
  std::set<int> frames;
  for (int quarter = 0; quarter <= 4; ++quarter) frames.insert(frame_count * quarter / 4);
  return {frames.begin(), frames.end()};
}

std::map<int, GoldenRows> read_golden_values(const std::filesystem::path& run_dir,
                                             const std::vector<int>& frames) {
  const std::set<int> chosen(frames.begin(), frames.end());
  std::map<int, GoldenRows> values;
  read_table(run_dir / "metrics.csv", {"solver"}, chosen, values);
  read_table(run_dir / "contacts.csv", {"solver", "collider"}, chosen, values);
  read_table(run_dir / "compare.csv", {"solver_a", "solver_b"}, chosen, values);
  return values;
}

std::vector<GoldenDifference> compare_golden(const Golden& golden,
                                             const std::map<int, GoldenRows>& actual) {
  std::vector<GoldenDifference> differences;
  static const GoldenRows kNoRows;
  static const std::map<std::string, std::optional<double>> kNoColumns;
  std::set<int> frames;
  for (const auto& [frame, rows] : golden.frames) frames.insert(frame);
  for (const auto& [frame, rows] : actual) frames.insert(frame);
  for (int frame : frames) {
    const auto expected_frame = golden.frames.find(frame);
    const auto actual_frame = actual.find(frame);
    const GoldenRows& expected_rows =
        expected_frame != golden.frames.end() ? expected_frame->second : kNoRows;
    const GoldenRows& actual_rows = actual_frame != actual.end() ? actual_frame->second : kNoRows;
    std::set<std::pair<std::string, std::string>> cells;
    for (const auto& [row, columns] : expected_rows)
      for (const auto& [column, value] : columns) cells.insert({row, column});
    for (const auto& [row, columns] : actual_rows)
      for (const auto& [column, value] : columns) cells.insert({row, column});
    for (const auto& [row, column] : cells) {
      auto lookup = [&](const GoldenRows& rows) -> std::optional<std::optional<double>> {
        const auto r = rows.find(row);
        if (r == rows.end()) return std::nullopt;
        const auto c = r->second.find(column);
        if (c == r->second.end()) return std::nullopt;
        return c->second;
      };
      const auto expected = lookup(expected_rows), found = lookup(actual_rows);
      const bool present_both = expected.has_value() && found.has_value();
      if (present_both && within(golden.tolerance, column, *expected, *found)) continue;
      differences.push_back(
          {frame, row, column, expected ? *expected : std::nullopt, found ? *found : std::nullopt});
    }
  }
  return differences;
}

std::string describe_difference(const GoldenDifference& d) {
  auto text = [](std::optional<double> v) { return v ? format_number(*v) : std::string("(none)"); };
  std::string line = "frame " + std::to_string(d.frame) + " " + d.row + " " + d.column + ": " +
                     text(d.expected) + " -> " + text(d.actual);
  if (d.expected && d.actual && *d.expected != 0.0) {
    char change[32];
    std::snprintf(change, sizeof change, " (%+.3g %%)",
                  100.0 * (*d.actual - *d.expected) / std::abs(*d.expected));
    line += change;
  }
  return line;
}

std::string golden_to_json(const Golden& golden) {
  ordered_json j;
  j["scene"] = golden.scene;
  j["overrides"] = golden.overrides;
  j["tolerance"] = {{"relative", golden.tolerance.relative},
                    {"absolute", golden.tolerance.absolute},
                    {"count", golden.tolerance.count}};
  ordered_json frames = ordered_json::object();
  for (const auto& [frame, rows] : golden.frames) {
    ordered_json frame_json = ordered_json::object();
    for (const auto& [row, columns] : rows) {
      ordered_json row_json = ordered_json::object();
      for (const auto& [column, value] : columns) row_json[column] = value_json(value);
      frame_json[row] = row_json;
    }
    frames[std::to_string(frame)] = frame_json;
  }
  j["frames"] = frames;
  return j.dump(2) + "\n";
}

std::optional<Golden> golden_from_json(const std::string& text, std::string* error) {
  const auto j = nlohmann::json::parse(text, nullptr, false);
  auto fail = [&](const std::string& message) -> std::optional<Golden> {
    if (error) *error = message;
    return std::nullopt;
  };
  if (j.is_discarded() || !j.is_object()) return fail("is not valid JSON");
  try {
    Golden golden;
    golden.scene = j.at("scene").get<std::string>();
    golden.overrides = j.at("overrides").get<std::vector<std::string>>();
    const auto& t = j.at("tolerance");
    golden.tolerance = {t.at("relative").get<double>(), t.at("absolute").get<double>(),
                        t.at("count").get<double>()};
    for (const auto& [frame, rows] : j.at("frames").items()) {
      GoldenRows& out = golden.frames[std::stoi(frame)];
      for (const auto& [row, columns] : rows.items())
        for (const auto& [column, value] : columns.items())
          out[row][column] =
              value.is_null() ? std::nullopt : std::optional<double>(value.get<double>());
    }
    return golden;
  } catch (const std::exception& e) {
    return fail(std::string("is not a drapelab golden file (") + e.what() + ")");
  }
}

}  // namespace drapelab::runner
