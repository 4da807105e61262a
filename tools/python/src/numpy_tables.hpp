// Tables as Python sees them: a dict from column name to a NumPy array, in the table's column
// order.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "drapelab/run_folder/csv.hpp"

namespace drapelab::python {

// A column is int64 when every cell is a whole number written without a point or exponent, float64
// when every non-empty cell is a number (an empty cell reads as NaN), and an array of str
// otherwise. `rows`, when given, picks and orders the rows.
pybind11::dict table_arrays(const run_folder::CsvTable& table);
pybind11::dict table_arrays(const run_folder::CsvTable& table,
                            const std::vector<std::size_t>& rows);

}  // namespace drapelab::python
