// Small queries and names of the model types.
#include "drapelab/cloth_model.hpp"

#include <algorithm>

namespace drapelab {

const char* spring_kind_name(SpringKind kind) {
  switch (kind) {
    case SpringKind::stretch:
      return "stretch";
    case SpringKind::shear:
      return "shear";
    case SpringKind::bend:
      return "bend";
  }
  return "unknown";
}

std::size_t SpringSet::count(SpringKind k) const {
  return static_cast<std::size_t>(std::count(kind.begin(), kind.end(), k));
}

std::string ClothModel::describe_particle(int i) const {
  std::string text = "particle " + std::to_string(i);
  if (grid.nx > 0)
    text += " (grid i=" + std::to_string(i % grid.nx) + ", j=" + std::to_string(i / grid.nx) + ")";
  return text;
}

}  // namespace drapelab
