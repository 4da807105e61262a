// OBJ and PC2 mesh outputs.
#include "drapelab/runner/mesh_output.hpp"

#include <sstream>

#include "drapelab/run_folder/output_file.hpp"
#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {

void write_obj(const std::filesystem::path& path, const ClothModel& model,
               const Eigen::Matrix3Xd& x, const std::string& comment) {
  std::ostringstream out;
  out << "# " << comment << "\n# vertex k is particle k (y up, metres)\n";
  for (Eigen::Index k = 0; k < x.cols(); ++k)
    out << "v " << format_number(x(0, k)) << ' ' << format_number(x(1, k)) << ' '
        << format_number(x(2, k)) << '\n';
  for (Eigen::Index k = 0; k < model.uvs.cols(); ++k)
    out << "vt " << format_number(model.uvs(0, k)) << ' ' << format_number(model.uvs(1, k)) << '\n';
  for (Eigen::Index t = 0; t < model.triangles.cols(); ++t) {
    out << 'f';
    for (int c = 0; c < 3; ++c)
      out << ' ' << model.triangles(c, t) + 1 << '/' << model.triangles(c, t) + 1;
    out << '\n';
  }
  if (model.triangles.cols() == 0 && x.cols() > 1) {  // a chain: one polyline through the particles
    out << 'l';
    for (Eigen::Index k = 0; k < x.cols(); ++k) out << ' ' << k + 1;
    out << '\n';
  }
  run_folder::write_whole_file(path, out.str());
}

}  // namespace drapelab::runner
