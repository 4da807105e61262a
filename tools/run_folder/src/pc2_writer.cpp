// Writing PC2 point caches a frame at a time (point_cache.hpp).
#include <cstdint>
#include <cstring>
#include <string>

#include "drapelab/run_folder/point_cache.hpp"

namespace drapelab::run_folder {
namespace {

constexpr std::int64_t kSampleCountAt = 12 + 4 + 4 + 4 + 4;  // signature .. sample rate

// The bytes of a value as PC2 stores it (x86-64 and aarch64 are little endian, as PC2 is).
template <typename T>
void put(std::string& bytes, T value) {
  char raw[sizeof value];
  std::memcpy(raw, &value, sizeof value);
  bytes.append(raw, sizeof value);
}

}  // namespace

Pc2Writer::Pc2Writer(const std::filesystem::path& path, int point_count)
    : file_(path), points_(point_count) {
  std::string header("POINTCACHE2", 12);  // 11 characters and the terminating zero
  put<std::int32_t>(header, 1);           // file version
  put<std::int32_t>(header, point_count);
  put<float>(header, 0.0f);      // start frame
  put<float>(header, 1.0f);      // one sample per recorded frame
  put<std::int32_t>(header, 0);  // samples so far
  file_.append(header);
  file_.commit();
}

void Pc2Writer::append(const Eigen::Matrix3Xd& x) {
  std::string sample;
  sample.reserve(std::size_t(points_) * 12);
  for (Eigen::Index k = 0; k < x.cols(); ++k)
    for (int c = 0; c < 3; ++c) put<float>(sample, static_cast<float>(x(c, k)));
  file_.append(sample);
  ++samples_;
  std::string count;
  put<std::int32_t>(count, samples_);
  file_.overwrite(kSampleCountAt, count);
}

void Pc2Writer::commit() {
  file_.commit();
  committed_samples_ = samples_;
}

bool Pc2Writer::rollback() noexcept {
  if (!file_.rollback()) return false;
  samples_ = committed_samples_;
  try {
    std::string count;
    put<std::int32_t>(count, samples_);
    file_.overwrite(kSampleCountAt, count);
  } catch (...) {
    return false;
  }
  return true;
}

}  // namespace drapelab::run_folder
