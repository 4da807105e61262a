// docs/scene-reference.md's key tables from the scene key table (key_tables.hpp).
#include "drapelab/scene/key_tables.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "drapelab/scene/number_format.hpp"
#include "scene_keys.hpp"

namespace drapelab::scene {
namespace {

constexpr std::string_view kOpen = "<!-- scene-keys:";
constexpr std::string_view kClose = "<!-- /scene-keys -->";
constexpr std::string_view kTop = "top";  // the top level's name in a marker
const char* const kColumns[] = {"key", "type", "default", "range", "unit", "meaning"};
constexpr std::size_t kColumnCount = std::size(kColumns);

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string word; in >> word;) out.push_back(word == kTop ? "" : word);
  return out;
}

// "10⁻⁶", "9.2 × 10¹⁸", "0.001", "−1000": a bound as the page writes numbers.
std::string page_number(double value) {
  static const char* const kSuperscripts[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string text = format_number(std::abs(value));
  const double exponent = std::round(std::log10(std::abs(value)));
  if (value != 0.0 && std::abs(value) >= 1e4 && std::pow(10.0, exponent) == std::abs(value))
    text = "1e" + std::to_string(static_cast<int>(exponent));  // 10000 as 10⁴
  if (const std::size_t e = text.find('e'); e != std::string::npos) {
    const std::string mantissa = text.substr(0, e);
    const int power = std::stoi(text.substr(e + 1));
    std::string digits = power < 0 ? "⁻" : "";
    for (char digit : std::to_string(std::abs(power))) digits += kSuperscripts[digit - '0'];
    text = (mantissa == "1" ? "" : mantissa + " × ") + "10" + digits;
  }
  return (value < 0.0 ? "−" : "") + text;
}

std::string page_range(const SceneKey& row) {
  if (row.type == KeyType::choice) {
    std::string text;
    for (const std::string& choice : key_choices(row))
      text += (text.empty() ? "`" : " \\| `") + choice + "`";
    return text;
  }
  const Range& r = row.range;
  std::string text;
  if (r.min && r.max)
    text = (r.min_inclusive ? "[" : "(") + page_number(*r.min) + ", " + page_number(*r.max) +
           (r.max_inclusive ? "]" : ")");
  else if (r.min)
    text = (r.min_inclusive ? "≥ " : "> ") + page_number(*r.min);
  else if (r.max)
    text = (r.max_inclusive ? "≤ " : "< ") + page_number(*r.max);
  const bool each = row.type == KeyType::numbers || row.type == KeyType::integers;
  return each && !text.empty() ? (r.min && r.max ? "each in " : "each ") + text : text;
}

std::string page_type(const SceneKey& row) {
  const std::string count = std::to_string(row.size);
  switch (row.type) {
    case KeyType::text:
      return "text";
    case KeyType::number:
      return "number";
    case KeyType::integer:
      return "whole number";
    case KeyType::boolean:
      return "`true` or `false`";
    case KeyType::choice:
      return "one of";
    case KeyType::numbers:
      return count + " numbers";
    case KeyType::integers:
      return count + " whole numbers";
    case KeyType::map:
      return "map";
    case KeyType::list:
      return "list";
  }
  return "";
}

std::string page_default(const SceneKey& row) {
  switch (row.given) {
    case Given::value:
      return "`" + std::string(row.fallback) + "`";
    case Given::required:
      return row.fallback.empty() ? "required" : std::string(row.fallback);
    case Given::optional:
      return row.fallback.empty() ? "none" : std::string(row.fallback);
    case Given::derived:
      break;
  }
  return std::string(row.fallback);
}

// "N*s/m" as "N·s/m", "m/s^2" as "m/s²".
std::string page_unit(std::string_view unit) {
  std::string text;
  for (std::size_t k = 0; k < unit.size(); ++k) {
    const bool power = unit[k] == '^' && k + 1 < unit.size();
    if (power && unit[k + 1] == '2')
      text += "²";
    else if (power && unit[k + 1] == '3')
      text += "³";
    else
      text += unit[k] == '*' ? std::string("·") : std::string(1, unit[k]);
    k += power ? 1 : 0;
  }
  return text;
}

std::vector<std::string> row_cells(const SceneKey& row, const std::string& first_parent) {
  const std::string path(row.path);
  const std::string shown = first_parent.empty() || path.size() <= first_parent.size()
                                ? path
                                : path.substr(first_parent.size() + 1);
  std::string meaning(row.doc);
  if (!row.when.empty()) {  // "`cylinder`, `capsule` only: ..."
    std::string when = "`" + std::string(row.when) + "`";
    for (std::size_t bar; (bar = when.find('|')) != std::string::npos;)
      when.replace(bar, 1, "`, `");
    meaning = when + " only: " + meaning;
  }
  return {"`" + shown + "`", page_type(row),      page_default(row),
          page_range(row),   page_unit(row.unit), meaning};
}

std::string table_line(const std::vector<std::string>& cells) {
  std::string line = "|";
  for (const std::string& cell : cells) line += " " + cell + " |";
  return line;
}

// The cells of a table line, split at the bars that are not escaped ("\|").
std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t k = 1; k < line.size(); ++k) {
    if (line[k] == '|' && line[k - 1] != '\\') {
      const std::size_t first = cell.find_first_not_of(' ');
      const std::size_t last = cell.find_last_not_of(' ');
      cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
      cell.clear();
    } else {
      cell += line[k];
    }
  }
  return cells;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

struct TableRow {
  std::string path;  // the key's whole path, for messages
  std::vector<std::string> cells;
};

// The rows of one marker's table: the keys of each of its maps in turn, in table order, each named
// from the first map.
std::vector<TableRow> table_rows(const std::vector<std::string>& parents) {
  std::vector<TableRow> rows;
  for (const std::string& parent : parents)
    for (const SceneKey* row : keys_under(parent))
      rows.push_back({std::string(row->path), row_cells(*row, parents.front())});
  return rows;
}

// The table of one marker, as lines: the header, its rule, the rows.
std::vector<std::string> table_lines(const std::vector<std::string>& parents) {
  std::vector<std::string> lines = {table_line({kColumns, kColumns + kColumnCount}),
                                    table_line(std::vector<std::string>(kColumnCount, "---"))};
  for (const TableRow& row : table_rows(parents)) lines.push_back(table_line(row.cells));
  return lines;
}

struct Block {
  std::string marker;               // the parents as the marker gives them
  std::size_t open = 0, close = 0;  // line indices of the markers
};

// The marked blocks of `lines`; a marker not closed is reported in `problems`.
std::vector<Block> blocks_of(const std::vector<std::string>& lines,
                             std::vector<std::string>* problems) {
  std::vector<Block> blocks;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (lines[k].rfind(kOpen, 0) != 0) continue;
    Block block;
    block.open = k;
    const std::size_t end = lines[k].rfind("-->");
    block.marker = lines[k].substr(
        kOpen.size(), end == std::string::npos ? std::string::npos : end - kOpen.size());
    block.marker.erase(0, block.marker.find_first_not_of(' '));
    block.marker.erase(block.marker.find_last_not_of(' ') + 1);
    while (++k < lines.size() && lines[k] != kClose && lines[k].rfind(kOpen, 0) != 0) {
    }
    if (k >= lines.size() || lines[k] != kClose) {
      if (problems)
        problems->push_back("line " + std::to_string(block.open + 1) + ": marker " +
                            lines[block.open] + " has no " + std::string(kClose));
      --k;
      continue;
    }
    block.close = k;
    blocks.push_back(block);
  }
  return blocks;
}

// The differences between one block of the page and the rows the table gives it.
void compare_block(const std::vector<std::string>& lines, const Block& block,
                   std::vector<std::string>& problems) {
  const std::vector<std::string> parents = words(block.marker);
  const std::string marker = "(" + std::string(kOpen.substr(5)) + " " + block.marker + ")";
  const std::vector<TableRow> rows = table_rows(parents);
  const std::vector<std::string> header = table_lines({});     // the header and the rule
  std::vector<std::string> page_keys;                          // in page order
  std::map<std::string, std::vector<std::string>> page_cells;  // key cell -> cells
  for (std::size_t k = block.open + 1; k < block.close; ++k) {
    const std::string& line = lines[k];
    const std::size_t row = k - block.open - 1;
    if (row < header.size()) {
      if (line != header[row])
        problems.push_back("line " + std::to_string(k + 1) + " " + marker +
                           ": the table's header is '" + header[row] + "', not '" + line + "'");
      continue;
    }
    const std::vector<std::string> cells = split_cells(line);
    if (line.rfind("| `", 0) != 0 || cells.size() != kColumnCount) {
      problems.push_back("line " + std::to_string(k + 1) + " " + marker + ": '" + line +
                         "' is not a row of " + std::to_string(kColumnCount) + " cells");
      continue;
    }
    page_keys.push_back(cells[0]);
    page_cells[cells[0]] = cells;
  }
  std::vector<std::string> table_keys;
  bool cells_differ = false;
  for (const TableRow& row : rows) {
    table_keys.push_back(row.cells[0]);
    const auto found = page_cells.find(row.cells[0]);
    if (found == page_cells.end()) {
      problems.push_back(row.path + ": missing from the page " + marker + "; its row is " +
                         table_line(row.cells));
      cells_differ = true;
      continue;
    }
    for (std::size_t c = 1; c < kColumnCount; ++c)
      if (found->second[c] != row.cells[c]) {
        problems.push_back(row.path + ": " + kColumns[c] + " is '" + found->second[c] +
                           "' on the page, '" + row.cells[c] + "' in the key table");
        cells_differ = true;
      }
  }
  for (const std::string& key : page_keys)
    if (std::find(table_keys.begin(), table_keys.end(), key) == table_keys.end()) {
      problems.push_back(key + " " + marker + ": on the page, but not a key of the key table");
      cells_differ = true;
    }
  if (!cells_differ && page_keys != table_keys)
    problems.push_back(marker + ": the rows are not in the key table's order (" +
                       (table_keys.empty() ? std::string() : table_keys.front()) + ", ...)");
}

}  // namespace

std::string key_table_markdown(const std::string& parents) {
  std::string text;
  for (const std::string& line : table_lines(words(parents))) text += line + "\n";
  return text;
}

std::string with_key_tables(const std::string& markdown) {
  const std::vector<std::string> lines = lines_of(markdown);
  std::string out;
  std::size_t next = 0;
  for (const Block& block : blocks_of(lines, nullptr)) {
    for (; next <= block.open; ++next) out += lines[next] + "\n";
    out += key_table_markdown(block.marker);
    next = block.close;
  }
  for (; next < lines.size(); ++next) out += lines[next] + "\n";
  return out;
}

std::vector<std::string> key_table_problems(const std::string& markdown) {
  std::vector<std::string> problems;
  const std::vector<std::string> lines = lines_of(markdown);
  std::vector<std::string> covered;  // the maps the page's tables list
  for (const Block& block : blocks_of(lines, &problems)) {
    compare_block(lines, block, problems);
    for (const std::string& parent : words(block.marker)) covered.push_back(parent);
  }
  for (const SceneKey* row : scene_keys())
    if (std::find(covered.begin(), covered.end(), row->parent()) == covered.end())
      problems.push_back(std::string(row->path) + ": in no table of the page (add " +
                         (row->parent().empty() ? std::string(kTop) : std::string(row->parent())) +
                         " to a " + std::string(kOpen) + " marker)");
  return problems;
}

}  // namespace drapelab::scene
