#include "drapelab/report/axis_ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace drapelab::report {
namespace {

// The smallest of 1, 2, 2.5, 5, 10 times a power of ten that is >= raw (raw > 0).
double nice_step(double raw) {
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  for (const double candidate : {1.0, 2.0, 2.5, 5.0})
    if (fraction <= candidate * (1.0 + 1e-9)) return candidate * power;
  return 10.0 * power;
}

}  // namespace

// "1e-05" -> "1e-5", "1e+05" -> "1e5": C's %g pads exponents to two digits with a sign.
std::string plain_exponent(const std::string& text) {
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e);
  std::size_t k = e + 1;
  std::string sign;
  if (k < text.size() && (text[k] == '+' || text[k] == '-')) {
    if (text[k] == '-') sign = "-";
    ++k;
  }
  while (k + 1 < text.size() && text[k] == '0') ++k;
  return mantissa + "e" + sign + text.substr(k);
}

namespace {

void label_all(AxisTicks& axis, double resolution) {
  axis.labels.clear();
  for (const double v : axis.values) axis.labels.push_back(tick_label(v, resolution));
}

}  // namespace

std::string tick_label(double value, double resolution) {
  if (value == 0.0) return "0";
  char buffer[64];
  // Between 1e-4 and 1e6 show every digit before the point (%g would write 200 as 2e+02).
  const double magnitude = std::fabs(value);
  int first_precision = 1;
  if (magnitude >= 1.0 && magnitude < 1e6)
    first_precision = static_cast<int>(std::floor(std::log10(magnitude))) + 1;
  for (int precision = first_precision; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    if (std::fabs(std::strtod(buffer, nullptr) - value) <= std::fabs(resolution)) break;
  }
  return plain_exponent(buffer);
}

AxisTicks linear_ticks(double data_min, double data_max, int target) {
  AxisTicks axis;
  if (!std::isfinite(data_min) || !std::isfinite(data_max) || data_min > data_max) {
    data_min = 0.0;
    data_max = 1.0;
  }
  if (data_max - data_min <= 1e-12 * std::max(std::fabs(data_min), std::fabs(data_max))) {
    // A constant series: widen by 5 % of its value (or by 1 around zero) so the line sits mid-plot.
    const double pad = data_min != 0.0 ? 0.05 * std::fabs(data_min) : 1.0;
    data_min -= pad;
    data_max += pad;
  }
  const double step = nice_step((data_max - data_min) / std::max(1, target));
  const double first = std::floor(data_min / step + 1e-9);
  const double last = std::ceil(data_max / step - 1e-9);
  axis.lo = first * step;
  axis.hi = last * step;
  for (double k = first; k <= last + 0.5; k += 1.0) {
    double v = k * step;  // from the integer k, so no rounding builds up along the axis
    if (std::fabs(v) < 1e-9 * step) v = 0.0;
    axis.values.push_back(v);
  }
  label_all(axis, 1e-6 * step);
  return axis;
}

AxisTicks log_ticks(double data_min, double data_max) {
  AxisTicks axis;
  axis.log = true;
  if (!(data_min > 0.0) || !std::isfinite(data_max) || data_max < data_min) {
    data_min = 1.0;
    data_max = 10.0;
  }
  const int first = static_cast<int>(std::floor(std::log10(data_min) + 1e-9));
  int last = static_cast<int>(std::ceil(std::log10(data_max) - 1e-9));
  if (last <= first) last = first + 1;
  axis.lo = std::pow(10.0, first);
  axis.hi = std::pow(10.0, last);
  const bool fine = last - first <= 2;
  for (int decade = first; decade <= last; ++decade) {
    const double power = std::pow(10.0, decade);
    axis.values.push_back(power);
    if (fine && decade < last) {
      axis.values.push_back(2.0 * power);
      axis.values.push_back(5.0 * power);
    }
  }
  axis.labels.clear();
  for (const double v : axis.values) axis.labels.push_back(tick_label(v, 1e-6 * v));
  return axis;
}

}  // namespace drapelab::report
