#include "drapelab/scene/number_format.hpp"

#include <charconv>
#include <cmath>

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

}  // namespace drapelab
