// Reading a run folder's frames: point caches, per-frame OBJ files, summary.json and metrics.csv.
#include "drapelab/render/run_frames.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::render {
namespace {

namespace fs = std::filesystem;

constexpr long kPc2HeaderBytes = 12 + 4 + 4 + 4 + 4 + 4;  // signature, version, points, start, rate, samples

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

class PointCache final : public FrameSource {
 public:
  PointCache(const fs::path& file, int particle_count) : file_(file), points_(particle_count) {
    std::FILE* f = std::fopen(file.string().c_str(), "rb");
    if (!f) throw std::runtime_error("cannot read " + file.string());
    char header[kPc2HeaderBytes];
    const bool whole = std::fread(header, 1, sizeof header, f) == sizeof header;
    std::fclose(f);
    std::int32_t version = 0, points = 0, samples = 0;
    if (whole) {
      std::memcpy(&version, header + 12, 4);  // little endian, as written (x86-64 and aarch64)
      std::memcpy(&points, header + 16, 4);
      std::memcpy(&samples, header + 28, 4);
    }
    if (!whole || std::memcmp(header, "POINTCACHE2", 12) != 0 || version != 1)
      throw RunInputError(file.string() + " is not a PC2 point cache (POINTCACHE2, version 1)");
    if (points != particle_count)
      throw RunInputError(file.string() + " holds " + std::to_string(points) + " points per frame, but the run's cloth (resolved.yaml) has " +
                          std::to_string(particle_count) + " particles");
    const auto bytes = static_cast<long long>(fs::file_size(file));
    const long long sample_bytes = 12LL * points;
    const long long complete = points > 0 ? (bytes - kPc2HeaderBytes) / sample_bytes : 0;
    samples_ = static_cast<int>(std::max(0LL, std::min<long long>(samples, complete)));
  }
  int frame_count() const override { return samples_; }
  std::string description() const override { return file_.filename().string(); }
  Eigen::Matrix3Xd positions(int frame) const override {
    std::vector<float> values(std::size_t(points_) * 3);
    std::FILE* f = std::fopen(file_.string().c_str(), "rb");
    if (!f) throw std::runtime_error("cannot read " + file_.string());
    const long offset = kPc2HeaderBytes + static_cast<long>(frame) * 12L * points_;
    const bool ok = std::fseek(f, offset, SEEK_SET) == 0 &&
                    std::fread(values.data(), sizeof(float), values.size(), f) == values.size();
    std::fclose(f);
    if (!ok) throw std::runtime_error("cannot read frame " + std::to_string(frame) + " of " + file_.string());
    return Eigen::Map<const Eigen::Matrix3Xf>(values.data(), 3, points_).cast<double>();
  }

 private:
  fs::path file_;
  int points_ = 0;
  int samples_ = 0;
};

std::string obj_frame_name(const std::string& solver, int frame) {
  char number[16];
  std::snprintf(number, sizeof number, "%04d", frame);  // as run_scene names them
  return solver + "_" + number + ".obj";
}

class ObjSequence final : public FrameSource {
 public:
  ObjSequence(const fs::path& folder, const std::string& solver, int particle_count)
      : folder_(folder), solver_(solver), points_(particle_count) {
    while (fs::exists(folder / obj_frame_name(solver, frames_))) ++frames_;
  }
  int frame_count() const override { return frames_; }
  std::string description() const override { return solver_ + "_NNNN.obj"; }
  Eigen::Matrix3Xd positions(int frame) const override {
    const fs::path file = folder_ / obj_frame_name(solver_, frame);
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file.string());
    Eigen::Matrix3Xd x(3, points_);
    int count = 0;
    std::string line;
    while (std::getline(in, line)) {
      if (line.size() < 2 || line[0] != 'v' || line[1] != ' ') continue;  // vertices only
      std::istringstream fields(line.substr(2));
      Eigen::Vector3d p;
      if (!(fields >> p.x() >> p.y() >> p.z())) throw std::runtime_error(file.string() + ": bad vertex line: " + line);
      if (count < points_) x.col(count) = p;
      ++count;
    }
    if (count != points_)
      throw std::runtime_error(file.string() + " has " + std::to_string(count) + " vertices, the cloth " +
                               std::to_string(points_) + " particles");
    return x;
  }

 private:
  fs::path folder_;
  std::string solver_;
  int points_ = 0;
  int frames_ = 0;
};

std::optional<double> parse_cell(const std::string& cell) {
  if (cell.empty()) return std::nullopt;
  try {
    return std::stod(cell);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// metrics.csv rows by solver and frame; only the columns the legend shows.
void read_metrics(const fs::path& file, std::vector<SolverFrames>& solvers) {
  std::ifstream in(file);
  if (!in) return;  // legends without metrics
  auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream stream(line);
    std::string cell;
    while (std::getline(stream, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    return cells;
  };
  std::string line;
  if (!std::getline(in, line)) return;
  const auto header = split(line);
  auto column = [&](const std::string& name) -> int {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return static_cast<int>(k);
    return -1;
  };
  const int solver_column = column("solver"), frame_column = column("frame"), time_column = column("time");
  const int stretch_column = column("max_stretch"), drape_column = column("drape_coefficient");
  if (solver_column < 0 || frame_column < 0) return;
  while (std::getline(in, line)) {
    const auto cells = split(line);
    auto cell = [&](int k) { return k >= 0 && k < int(cells.size()) ? cells[k] : std::string(); };
    for (auto& solver : solvers) {
      if (solver.name != cell(solver_column)) continue;
      const auto frame = parse_cell(cell(frame_column));
      if (!frame) break;
      FrameMetrics metrics;
      metrics.time = parse_cell(cell(time_column)).value_or(0.0);
      metrics.max_stretch = parse_cell(cell(stretch_column));
      metrics.drape_coefficient = parse_cell(cell(drape_column));
      solver.metrics[static_cast<int>(*frame)] = metrics;
    }
  }
}

}  // namespace

std::unique_ptr<FrameSource> open_point_cache(const fs::path& file, int particle_count) {
  return std::make_unique<PointCache>(file, particle_count);
}

std::unique_ptr<FrameSource> open_obj_sequence(const fs::path& folder, const std::string& solver,
                                               int particle_count) {
  return std::make_unique<ObjSequence>(folder, solver, particle_count);
}

RunFrames load_run_frames(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw RunInputError(dir.string() + " is not a folder (give a run folder written by drapelab run)");
  const fs::path resolved = dir / "resolved.yaml", summary_file = dir / "summary.json";
  if (!fs::exists(resolved) || !fs::exists(summary_file))
    throw RunInputError(dir.string() + " is not a run folder: it has no resolved.yaml or summary.json (write one with drapelab run SCENE --out " +
                        dir.string() + " --meshes pc2)");
  auto loaded = scene::load_scene_file(resolved);
  if (!loaded.ok()) {
    std::string message = "the run's resolved.yaml does not load:";
    for (const auto& error : loaded.errors) message += "\n  " + error;
    throw RunInputError(message);
  }
  RunFrames run;
  run.dir = dir;
  run.scene = std::move(*loaded.scene);
  run.model = scene::build_scene_cloth(run.scene);

  const auto summary = nlohmann::ordered_json::parse(read_text(summary_file), nullptr, false);
  if (summary.is_discarded() || !summary.contains("solvers") || !summary["solvers"].is_object())
    throw RunInputError(summary_file.string() + " is not a drapelab summary (no solvers object)");
  const fs::path meshes = dir / "meshes";
  std::vector<std::string> missing;
  for (const auto& [name, entry] : summary["solvers"].items()) {
    SolverFrames solver;
    solver.name = name;
    solver.type = entry.value("type", "");
    solver.status = entry.value("status", "");
    const fs::path cache = meshes / (name + ".pc2");
    if (fs::exists(cache)) solver.source = open_point_cache(cache, run.model.particle_count());
    else if (fs::exists(meshes / obj_frame_name(name, 0)))
      solver.source = open_obj_sequence(meshes, name, run.model.particle_count());
    else missing.push_back(name);
    run.solvers.push_back(std::move(solver));
  }
  if (run.solvers.empty()) throw RunInputError(summary_file.string() + " lists no solver");
  if (!missing.empty()) {
    std::string names;
    for (const auto& name : missing) names += (names.empty() ? "'" : ", '") + name + "'";
    throw RunInputError(dir.string() + " has no positions to draw for " + names +
                        ": neither a point cache (meshes/SOLVER.pc2) nor per-frame OBJ files (meshes/SOLVER_NNNN.obj). "
                        "Run the scene again with them: drapelab run SCENE --out " + dir.string() +
                        " --meshes pc2 (or output.meshes: pc2 in the scene)");
  }
  for (const auto& solver : run.solvers) run.frame_count = std::max(run.frame_count, solver.source->frame_count());
  if (run.frame_count == 0) throw RunInputError(dir.string() + ": the point caches hold no frame yet");
  read_metrics(dir / "metrics.csv", run.solvers);
  return run;
}

}  // namespace drapelab::render
