// OBJ and PC2 mesh outputs.
#include "drapelab/runner/mesh_output.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {

void write_obj(const std::filesystem::path& path, const ClothModel& model, const Eigen::Matrix3Xd& x,
               const std::string& comment) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  out << "# " << comment << "\n# vertex k is particle k (y up, metres)\n";
  for (Eigen::Index k = 0; k < x.cols(); ++k)
    out << "v " << format_number(x(0, k)) << ' ' << format_number(x(1, k)) << ' ' << format_number(x(2, k)) << '\n';
  for (Eigen::Index k = 0; k < model.uvs.cols(); ++k)
    out << "vt " << format_number(model.uvs(0, k)) << ' ' << format_number(model.uvs(1, k)) << '\n';
  for (Eigen::Index t = 0; t < model.triangles.cols(); ++t) {
    out << 'f';
    for (int c = 0; c < 3; ++c) out << ' ' << model.triangles(c, t) + 1 << '/' << model.triangles(c, t) + 1;
    out << '\n';
  }
  if (model.triangles.cols() == 0 && x.cols() > 1) {  // a chain: one polyline through the particles
    out << 'l';
    for (Eigen::Index k = 0; k < x.cols(); ++k) out << ' ' << k + 1;
    out << '\n';
  }
}

namespace {

void write_bytes(std::FILE* file, const void* data, std::size_t size) {
  if (std::fwrite(data, 1, size, file) != size) throw std::runtime_error("cannot write the point cache");
}

template <typename T>
void write_value(std::FILE* file, T value) {  // x86-64 and aarch64 are little endian, as PC2 is
  write_bytes(file, &value, sizeof value);
}

constexpr long kSampleCountOffset = 12 + 4 + 4 + 4 + 4;  // signature, version, points, start, rate

}  // namespace

Pc2Writer::Pc2Writer(const std::filesystem::path& path, int point_count) : points_(point_count) {
  file_ = std::fopen(path.string().c_str(), "wb");
  if (!file_) throw std::runtime_error("cannot write " + path.string());
  const char signature[12] = "POINTCACHE2";  // 11 characters and the terminating zero
  write_bytes(file_, signature, sizeof signature);
  write_value<std::int32_t>(file_, 1);             // file version
  write_value<std::int32_t>(file_, point_count);
  write_value<float>(file_, 0.0f);                  // start frame
  write_value<float>(file_, 1.0f);                  // one sample per recorded frame
  write_value<std::int32_t>(file_, 0);             // samples so far
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

}  // namespace drapelab::runner
