#include "drapelab/scene/number_format.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace drapelab {

std::string format_number(double value) {
  if (value == 0.0) return "0";  // also turns -0 into 0, so files do not differ by a sign of zero
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);  // shortest round trip
  return std::string(buffer, result.ptr);
}

std::string format_list(const Eigen::VectorXd& values) {
  std::string text = "[";
  for (Eigen::Index k = 0; k < values.size(); ++k)
    text += (k ? ", " : "") + format_number(values[k]);
  return text + "]";
}

std::string format_figures(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

std::string describe_seconds(double seconds) {
  char buffer[32];
  const auto two_figures = [&](double value, const char* unit) {
    std::snprintf(buffer, sizeof buffer, value < 10.0 ? "%.1f %s" : "%.0f %s", value, unit);
    return std::string(buffer);
  };
  if (!(seconds < 120.0)) {
    const double minutes = seconds / 60.0;
    return minutes < 120.0 ? two_figures(minutes, "min") : two_figures(minutes / 60.0, "h");
  }
  return two_figures(seconds, "s");
}

}  // namespace drapelab
