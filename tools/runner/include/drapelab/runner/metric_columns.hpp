// The per-frame measures of a solver in the order and under the names of metrics.csv's columns
// after solver, frame and time (docs/outputs.md). One table, so that metrics.csv and the Python
// module's arrays cannot disagree on a name or a value.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_metrics.hpp"

namespace drapelab::runner {

struct MetricColumn {
  std::string name;
  // The value, in the unit docs/metrics.md gives; empty where metrics.csv leaves the cell empty
  // (a measure the scene does not have: clearance without colliders, ...). Counts are whole
  // numbers.
  std::optional<double> (*value)(const ClothMetrics& metrics);
};

const std::vector<MetricColumn>& metric_columns();

}  // namespace drapelab::runner
