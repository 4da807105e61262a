// Numbers as text, in the shortest form that reads back as the same double.
#pragma once

#include <Eigen/Core>
#include <string>

namespace drapelab {

std::string format_number(double value);
// "[a, b, c]", each number as format_number writes it.
std::string format_list(const Eigen::VectorXd& values);
// A computed quantity for people, to four significant figures: "0.0175", "1.005", "6.768e-05".
std::string format_figures(double value);
// A duration for people, to two significant figures: "0.8 s", "40 s", "13 min", "2.5 h".
std::string describe_seconds(double seconds);

}  // namespace drapelab
