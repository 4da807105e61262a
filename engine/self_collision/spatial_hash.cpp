// The self-collision broad phase's grid (spatial_hash.hpp).
#include "self_collision/spatial_hash.hpp"

#include <algorithm>
#include <cmath>

namespace drapelab {
namespace {

constexpr double kCellLimit = 1048575.0;  // 2^20 - 1: each coordinate gets 21 bits
constexpr std::uint64_t kCellOffset = 1048576;

std::uint64_t cell_coordinate(double value, double inverse_cell_size) {
  const double cell = std::clamp(std::floor(value * inverse_cell_size), -kCellLimit, kCellLimit);
  return static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) +
                                    static_cast<std::int64_t>(kCellOffset));
}

}  // namespace

Box box_of(std::initializer_list<Eigen::Vector3d> points, double inflate) {
  Box box{*points.begin(), *points.begin()};
  for (const Eigen::Vector3d& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  box.min.array() -= inflate;
  box.max.array() += inflate;
  return box;
}

double cell_size_for(std::span<const Box> boxes, double at_least) {
  double sum = 0.0;
  for (const Box& box : boxes) sum += (box.max - box.min).maxCoeff();
  return std::max(at_least, boxes.empty() ? at_least : sum / static_cast<double>(boxes.size()));
}

std::uint64_t cell_key(const Eigen::Vector3d& p, double inverse_cell_size) {
  return (cell_coordinate(p.x(), inverse_cell_size) << 42) |
         (cell_coordinate(p.y(), inverse_cell_size) << 21) |
         cell_coordinate(p.z(), inverse_cell_size);
}

std::size_t SpatialGrid::bucket_of(std::uint64_t cell) const {
  // Fibonacci hashing: the product's top bits depend on every bit of the key.
  return static_cast<std::size_t>((cell * 0x9E3779B97F4A7C15ull) >> bucket_shift_);
}

void SpatialGrid::build(std::span<const Box> boxes, double cell_size) {
  inverse_cell_size_ = 1.0 / cell_size;
  unsorted_cells_.clear();
  unsorted_items_.clear();
  lowest_cell_.resize(boxes.size());
  for (std::size_t item = 0; item < boxes.size(); ++item) {
    const Box& box = boxes[item];
    const std::uint64_t low[3] = {cell_coordinate(box.min.x(), inverse_cell_size_),
                                  cell_coordinate(box.min.y(), inverse_cell_size_),
                                  cell_coordinate(box.min.z(), inverse_cell_size_)};
    const std::uint64_t high[3] = {cell_coordinate(box.max.x(), inverse_cell_size_),
                                   cell_coordinate(box.max.y(), inverse_cell_size_),
                                   cell_coordinate(box.max.z(), inverse_cell_size_)};
    lowest_cell_[item] = {low[0], low[1], low[2]};
    for (std::uint64_t i = low[0]; i <= high[0]; ++i)
      for (std::uint64_t j = low[1]; j <= high[1]; ++j)
        for (std::uint64_t k = low[2]; k <= high[2]; ++k) {
          unsorted_cells_.push_back((i << 42) | (j << 21) | k);
          unsorted_items_.push_back(static_cast<std::int32_t>(item));
        }
  }
  // A table of at least twice the entries, so most buckets hold one cell.
  std::size_t table = 64;
  bucket_shift_ = 58;
  while (table < 2 * unsorted_cells_.size()) {
    table *= 2;
    --bucket_shift_;
  }
  bucket_start_.assign(table + 1, 0);
  for (const std::uint64_t cell : unsorted_cells_) ++bucket_start_[bucket_of(cell) + 1];
  for (std::size_t b = 0; b < table; ++b) bucket_start_[b + 1] += bucket_start_[b];
  cells_.resize(unsorted_cells_.size());
  items_.resize(unsorted_cells_.size());
  entry_boxes_.resize(unsorted_cells_.size());
  // Counting sort; entries keep their box order within a bucket.
  std::vector<std::uint32_t>& next = fill_position_;
  next.assign(bucket_start_.begin(), bucket_start_.end() - 1);
  for (std::size_t e = 0; e < unsorted_cells_.size(); ++e) {
    const std::uint32_t at = next[bucket_of(unsorted_cells_[e])]++;
    cells_[at] = unsorted_cells_[e];
    items_[at] = unsorted_items_[e];
    entry_boxes_[at] = boxes[static_cast<std::size_t>(unsorted_items_[e])];
  }
}

std::array<std::uint64_t, 3> SpatialGrid::cell_of(const Eigen::Vector3d& p) const {
  return {cell_coordinate(p.x(), inverse_cell_size_), cell_coordinate(p.y(), inverse_cell_size_),
          cell_coordinate(p.z(), inverse_cell_size_)};
}

std::span<const std::int32_t> SpatialGrid::items_near(const Eigen::Vector3d& p) const {
  const std::size_t bucket = bucket_of(cell_key(p, inverse_cell_size_));
  const std::uint32_t begin = bucket_start_[bucket], end = bucket_start_[bucket + 1];
  return {items_.data() + begin, static_cast<std::size_t>(end - begin)};
}

}  // namespace drapelab
