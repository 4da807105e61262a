// The broad phase of self-collision: a spatial hash (Teschner et al., "Optimized Spatial Hashing
// for Collision Detection of Deformable Objects", 2003). Each box is entered in every grid cell it
// overlaps; the entries are counting-sorted by the hash of their cell into a table twice their
// number, so a rebuild is linear in the entries and a lookup is one bucket. Cells that share a
// bucket only cost extra box tests.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

namespace drapelab {

struct Box {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d max = Eigen::Vector3d::Zero();  // m

  bool overlaps(const Box& other) const {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }
  bool contains(const Eigen::Vector3d& p) const {
    return (min.array() <= p.array()).all() && (p.array() <= max.array()).all();
  }
};

// The box around `points`, grown by `inflate` (m) on every side.
Box box_of(std::initializer_list<Eigen::Vector3d> points, double inflate);
// A grid cell for `boxes`: their mean size, so a box covers a few cells, and at least `at_least`
// (m).
double cell_size_for(std::span<const Box> boxes, double at_least);

// Integer cell coordinates packed into one key. Coordinates beyond +-2^20 cells are clamped: far
// cells then share keys, which costs only extra narrow-phase tests, never a missed pair.
std::uint64_t cell_key(const Eigen::Vector3d& p, double inverse_cell_size);

class SpatialGrid {
 public:
  // Enters every box in each cell of `cell_size` m it overlaps. Allocates only to grow.
  void build(std::span<const Box> boxes, double cell_size);
  // The items entered in the bucket of the cell holding p: every item whose box overlaps that
  // cell, and perhaps others (test their boxes).
  std::span<const std::int32_t> items_near(const Eigen::Vector3d& p) const;
  // Calls visit(item) once for every item whose box contains p (and no other).
  template <typename Visit>
  void for_each_item_containing(const Eigen::Vector3d& p, Visit&& visit) const {
    const std::uint64_t cell = cell_key(p, inverse_cell_size_);
    const std::size_t bucket = bucket_of(cell);
    for (std::uint32_t e = bucket_start_[bucket]; e < bucket_start_[bucket + 1]; ++e)
      if (cells_[e] == cell && entry_boxes_[e].contains(p)) visit(items_[e]);
  }
  // Calls visit(item) once for every item whose box overlaps `query` (in the one cell that holds
  // the lowest corner of their overlap). Cost: the cells the query covers and their entries.
  template <typename Visit>
  void for_each_item_overlapping(const Box& query, Visit&& visit) const;
  // Calls visit(a, b) once for every pair of items a != b whose boxes overlap (in the one cell
  // that holds the lowest corner of the boxes' overlap).
  template <typename Visit>
  void for_each_overlapping_pair(Visit&& visit) const {
    for_each_overlapping_pair(0, bucket_count(), visit);
  }
  // The same for the pairs whose cell hashes to a bucket in [first_bucket, end_bucket): disjoint
  // ranges of buckets visit disjoint sets of pairs, so threads can share the buckets.
  template <typename Visit>
  void for_each_overlapping_pair(std::size_t first_bucket, std::size_t end_bucket,
                                 Visit&& visit) const;

  std::size_t entries() const { return items_.size(); }
  std::size_t bucket_count() const { return bucket_start_.empty() ? 0 : bucket_start_.size() - 1; }

 private:
  std::size_t bucket_of(std::uint64_t cell) const;
  std::array<std::uint64_t, 3> cell_of(const Eigen::Vector3d& p) const;

  double inverse_cell_size_ = 1.0;  // 1/m
  int bucket_shift_ = 58;           // 64 - log2(table size): the hash keeps the product's top bits
  std::vector<std::uint32_t> bucket_start_;  // per bucket, its first entry; one extra at the end
  std::vector<std::uint64_t> cells_;         // per entry (bucket order), its cell's key
  std::vector<std::int32_t> items_;          // per entry (bucket order), its item
  // Per entry (bucket order), its item's box: a search reads them in the order it scans the
  // entries, where reading each item's box from the caller's array was a cache miss an entry
  // (most of the edge-edge search's time on a 65 x 65 heap).
  std::vector<Box> entry_boxes_;
  std::vector<std::uint64_t> unsorted_cells_;  // scratch: entries in box order
  std::vector<std::int32_t> unsorted_items_;
  std::vector<std::array<std::uint64_t, 3>> lowest_cell_;  // per item, its box's lowest cell
  std::vector<std::uint32_t> fill_position_;  // scratch: per bucket, where its next entry goes
};

template <typename Visit>
void SpatialGrid::for_each_overlapping_pair(std::size_t first_bucket, std::size_t end_bucket,
                                            Visit&& visit) const {
  for (std::size_t bucket = first_bucket; bucket < end_bucket; ++bucket) {
    const std::uint32_t begin = bucket_start_[bucket], end = bucket_start_[bucket + 1];
    for (std::uint32_t i = begin; i < end; ++i)
      for (std::uint32_t j = i + 1; j < end; ++j) {
        if (cells_[i] != cells_[j]) continue;  // two cells sharing the bucket
        if (!entry_boxes_[i].overlaps(entry_boxes_[j])) continue;
        const std::int32_t a = items_[i], b = items_[j];
        // The overlap's lowest corner lies in the cell of the larger of the two lowest cells, axis
        // by axis (the cell index is monotonic in the coordinate).
        const auto& low_a = lowest_cell_[static_cast<std::size_t>(a)];
        const auto& low_b = lowest_cell_[static_cast<std::size_t>(b)];
        const std::uint64_t lowest = (std::max(low_a[0], low_b[0]) << 42) |
                                     (std::max(low_a[1], low_b[1]) << 21) |
                                     std::max(low_a[2], low_b[2]);
        if (lowest != cells_[i]) continue;
        visit(a, b);
      }
  }
}

template <typename Visit>
void SpatialGrid::for_each_item_overlapping(const Box& query, Visit&& visit) const {
  const std::array<std::uint64_t, 3> low = cell_of(query.min), high = cell_of(query.max);
  for (std::uint64_t i = low[0]; i <= high[0]; ++i)
    for (std::uint64_t j = low[1]; j <= high[1]; ++j)
      for (std::uint64_t k = low[2]; k <= high[2]; ++k) {
        const std::uint64_t cell = (i << 42) | (j << 21) | k;
        const std::size_t bucket = bucket_of(cell);
        for (std::uint32_t e = bucket_start_[bucket]; e < bucket_start_[bucket + 1]; ++e) {
          if (cells_[e] != cell) continue;
          if (!entry_boxes_[e].overlaps(query)) continue;
          const std::int32_t item = items_[e];
          const auto& item_low = lowest_cell_[static_cast<std::size_t>(item)];
          const std::uint64_t lowest = (std::max(low[0], item_low[0]) << 42) |
                                       (std::max(low[1], item_low[1]) << 21) |
                                       std::max(low[2], item_low[2]);
          if (lowest == cell) visit(item);
        }
      }
}

}  // namespace drapelab
