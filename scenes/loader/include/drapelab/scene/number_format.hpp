// Numbers as text, in the shortest form that reads back as the same double.
#pragma once

#include <string>

namespace drapelab {

std::string format_number(double value);

}  // namespace drapelab
