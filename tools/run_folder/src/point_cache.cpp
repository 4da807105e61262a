// PC2 point caches and mesh file names (point_cache.hpp).
#include "drapelab/run_folder/point_cache.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace drapelab::run_folder {

namespace {

void write_bytes(std::FILE* file, const void* data, std::size_t size) {
  if (std::fwrite(data, 1, size, file) != size)
    throw std::runtime_error("cannot write the point cache");
}

template <typename T>
void write_value(std::FILE* file, T value) {  // x86-64 and aarch64 are little endian, as PC2 is
  write_bytes(file, &value, sizeof value);
}

constexpr long kSampleCountOffset = 12 + 4 + 4 + 4 + 4;  // signature, version, points, start, rate
constexpr long kHeaderBytes = kSampleCountOffset + 4;    // and the sample count

}  // namespace

Pc2Writer::Pc2Writer(const std::filesystem::path& path, int point_count) : points_(point_count) {
  file_ = std::fopen(path.string().c_str(), "wb");
  if (!file_) throw std::runtime_error("cannot write " + path.string());
  const char signature[12] = "POINTCACHE2";  // 11 characters and the terminating zero
  write_bytes(file_, signature, sizeof signature);
  write_value<std::int32_t>(file_, 1);  // file version
  write_value<std::int32_t>(file_, point_count);
  write_value<float>(file_, 0.0f);      // start frame
  write_value<float>(file_, 1.0f);      // one sample per recorded frame
  write_value<std::int32_t>(file_, 0);  // samples so far
  std::fflush(file_);
}

Pc2Writer::~Pc2Writer() {
  if (file_) std::fclose(file_);
}

void Pc2Writer::append(const Eigen::Matrix3Xd& x) {
  std::fseek(file_, 0, SEEK_END);
  for (Eigen::Index k = 0; k < x.cols(); ++k)
    for (int c = 0; c < 3; ++c) write_value<float>(file_, static_cast<float>(x(c, k)));
  ++samples_;
  std::fseek(file_, kSampleCountOffset, SEEK_SET);
  write_value<std::int32_t>(file_, samples_);
  std::fflush(file_);
}

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
