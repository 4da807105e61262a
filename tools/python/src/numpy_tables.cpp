#include "numpy_tables.hpp"

#include <pybind11/numpy.h>

#include <cstdint>
#include <numeric>

namespace py = pybind11;

namespace drapelab::python {
namespace {

enum class ColumnKind { integer, number, text };

bool is_whole_number_text(const std::string& cell) {
  if (cell.empty()) return false;
  const std::size_t first = cell[0] == '-' ? 1 : 0;
  if (first == cell.size() || cell.size() - first > 18) return false;  // within int64
  for (std::size_t k = first; k < cell.size(); ++k)
    if (cell[k] < '0' || cell[k] > '9') return false;
  return true;
}

ColumnKind column_kind(const run_folder::CsvTable& table, std::size_t column,
                       const std::vector<std::size_t>& rows) {
  bool whole = !rows.empty();
  for (const std::size_t row : rows) {
    const std::string& cell = table.rows[row][column];
    if (cell.empty()) {
      whole = false;
      continue;
    }
    if (!run_folder::parse_number(cell)) return ColumnKind::text;
    whole = whole && is_whole_number_text(cell);
  }
  return whole ? ColumnKind::integer : ColumnKind::number;
}

}  // namespace

py::dict table_arrays(const run_folder::CsvTable& table) {
  std::vector<std::size_t> rows(table.rows.size());
  std::iota(rows.begin(), rows.end(), std::size_t{0});
  return table_arrays(table, rows);
}

py::dict table_arrays(const run_folder::CsvTable& table, const std::vector<std::size_t>& rows) {
  py::dict columns;
  const auto count = static_cast<py::ssize_t>(rows.size());
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    switch (column_kind(table, c, rows)) {
      case ColumnKind::integer: {
        py::array_t<std::int64_t> values(count);
        auto out = values.mutable_unchecked<1>();
        for (py::ssize_t k = 0; k < count; ++k)
          out(k) = std::stoll(table.rows[rows[static_cast<std::size_t>(k)]][c]);
        columns[py::str(table.header[c])] = values;
        break;
      }
      case ColumnKind::number: {
        py::array_t<double> values(count);
        auto out = values.mutable_unchecked<1>();
        for (py::ssize_t k = 0; k < count; ++k)
          out(k) = table.number(rows[static_cast<std::size_t>(k)], c);
        columns[py::str(table.header[c])] = values;
        break;
      }
      case ColumnKind::text: {
        py::list cells;
        for (const std::size_t row : rows) cells.append(py::str(table.rows[row][c]));
        columns[py::str(table.header[c])] =
            py::module_::import("numpy").attr("array")(cells, "str");
        break;
      }
    }
  }
  return columns;
}

}  // namespace drapelab::python
