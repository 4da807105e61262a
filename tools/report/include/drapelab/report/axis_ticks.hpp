// Axis ranges and tick marks for the report's plots: "nice" linear ticks (steps of 1, 2, 2.5 or 5
// times a power of ten) and decade ticks on a log axis, with labels just precise enough to tell the
// ticks apart.
#pragma once

#include <string>
#include <vector>

namespace drapelab::report {

struct AxisTicks {
  double lo = 0.0, hi = 1.0;  // the axis range, in data units (positive on a log axis)
  bool log = false;
  std::vector<double> values;       // tick positions, lo <= value <= hi, increasing
  std::vector<std::string> labels;  // one per tick
};

// Ticks covering [data_min, data_max] with about `target` intervals. Non-finite input gives [0, 1];
// an empty range is widened around its value.
AxisTicks linear_ticks(double data_min, double data_max, int target = 5);

// Decade ticks covering [data_min, data_max] (both > 0), with 2 and 5 between when the range spans
// at most two decades.
AxisTicks log_ticks(double data_min, double data_max);

// "1e-05" -> "1e-5", "1e+05" -> "1e5" (C's %g writes two exponent digits and a sign).
std::string plain_exponent(const std::string& text);

// The shortest %g text of `value` that reads back within `resolution` of it, with the exponent
// written plainly (1e-05 -> 1e-5, 1e+05 -> 1e5).
std::string tick_label(double value, double resolution);

}  // namespace drapelab::report
