// PC2 point caches and mesh file names (point_cache.hpp).
#include "drapelab/run_folder/point_cache.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace drapelab::run_folder {

namespace {

constexpr long kSampleCountOffset = 12 + 4 + 4 + 4 + 4;  // signature, version, points, start, rate
constexpr long kHeaderBytes = kSampleCountOffset + 4;    // and the sample count

}  // namespace

std::string point_cache_name(const std::string& solver) { return solver + ".pc2"; }

std::string obj_frame_name(const std::string& solver, int frame) {
  char number[16];
  std::snprintf(number, sizeof number, "%04d", frame);
  return solver + "_" + number + ".obj";
}

std::optional<Pc2Header> read_pc2_header(const std::filesystem::path& path) {
  std::FILE* f = std::fopen(path.string().c_str(), "rb");
  if (!f) return std::nullopt;
  char header[kHeaderBytes];
  const bool whole = std::fread(header, 1, sizeof header, f) == sizeof header;
  std::fclose(f);
  if (!whole || std::memcmp(header, "POINTCACHE2", 12) != 0) return std::nullopt;
  std::int32_t version = 0, points = 0, samples = 0;
  std::memcpy(&version, header + 12, 4);  // little endian, as written (x86-64 and aarch64)
  std::memcpy(&points, header + 16, 4);
  std::memcpy(&samples, header + kSampleCountOffset, 4);
  if (version != 1) return std::nullopt;
  const auto bytes = static_cast<long long>(std::filesystem::file_size(path));
  const long long sample_bytes = 12LL * points;
  const long long complete = points > 0 ? (bytes - kHeaderBytes) / sample_bytes : 0;
  return Pc2Header{points, static_cast<int>(std::max(0LL, std::min<long long>(samples, complete)))};
}

std::optional<Eigen::Matrix3Xd> read_pc2_frame(const std::filesystem::path& path, int points,
                                               int frame) {
  std::vector<float> values(std::size_t(points) * 3);
  std::FILE* f = std::fopen(path.string().c_str(), "rb");
  if (!f) return std::nullopt;
  const long offset = kHeaderBytes + static_cast<long>(frame) * 12L * points;
  const bool ok = std::fseek(f, offset, SEEK_SET) == 0 &&
                  std::fread(values.data(), sizeof(float), values.size(), f) == values.size();
  std::fclose(f);
  if (!ok) return std::nullopt;
  return Eigen::Map<const Eigen::Matrix3Xf>(values.data(), 3, points).cast<double>();
}

}  // namespace drapelab::run_folder
