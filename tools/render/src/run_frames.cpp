// Reading a run folder's frames: point caches, per-frame OBJ files, summary.json and metrics.csv.
#include "drapelab/render/run_frames.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/point_cache.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::render {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  auto text = run_folder::read_file_bytes(path);
  if (!text) throw std::runtime_error("cannot read " + path.string());
  return std::move(*text);
}

// The sample count a PC2 header claims (bytes 28 to 31, little endian as written), before it is
// capped by the file's size; nullopt when it cannot be read.
std::optional<std::int32_t> pc2_claimed_samples(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char bytes[4];
  if (!in.seekg(28) || !in.read(bytes, 4)) return std::nullopt;
  std::int32_t samples = 0;
  std::memcpy(&samples, bytes, 4);
  return samples;
}

class PointCache final : public FrameSource {
 public:
  PointCache(const fs::path& file, int particle_count) : file_(file), points_(particle_count) {
    if (!fs::exists(file)) throw std::runtime_error("cannot read " + file.string());
    const auto header = run_folder::read_pc2_header(file);
    if (!header)
      throw RunInputError(file.string() + " is not a PC2 point cache (POINTCACHE2, version 1)");
    if (header->points != particle_count)
      throw RunInputError(file.string() + " holds " + std::to_string(header->points) +
                          " points per frame, but the run's cloth (resolved.yaml) has " +
                          std::to_string(particle_count) + " particles");
    samples_ = header->samples;
    // The writer rewrites the count after each whole frame, so a count above the whole frames in
    // the file means the file was cut after it was written.
    const auto claimed = pc2_claimed_samples(file);
    if (claimed && *claimed > samples_)
      throw RunInputError(
          file.string() + " is cut short: its header says " + std::to_string(*claimed) +
          " frames, but the file holds " + std::to_string(samples_) + " whole frames (" +
          std::to_string(fs::file_size(file)) + " bytes); run the scene again with --meshes pc2");
  }
  int frame_count() const override { return samples_; }
  std::string description() const override { return file_.filename().string(); }
  Eigen::Matrix3Xd positions(int frame) const override {
    auto x = run_folder::read_pc2_frame(file_, points_, frame);
    if (!x)
      throw std::runtime_error("cannot read frame " + std::to_string(frame) + " of " +
                               file_.string());
    return *x;
  }

 private:
  fs::path file_;
  int points_ = 0;
  int samples_ = 0;
};

class ObjSequence final : public FrameSource {
 public:
  ObjSequence(const fs::path& folder, const std::string& solver, int particle_count)
      : folder_(folder), solver_(solver), points_(particle_count) {
    while (fs::exists(folder / run_folder::obj_frame_name(solver, frames_))) ++frames_;
  }
  int frame_count() const override { return frames_; }
  std::string description() const override { return solver_ + "_NNNN.obj"; }
  Eigen::Matrix3Xd positions(int frame) const override {
    const fs::path file = folder_ / run_folder::obj_frame_name(solver_, frame);
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file.string());
    Eigen::Matrix3Xd x(3, points_);
    int count = 0;
    std::string line;
    while (std::getline(in, line)) {
      if (line.size() < 2 || line[0] != 'v' || line[1] != ' ') continue;  // vertices only
      std::istringstream fields(line.substr(2));
      Eigen::Vector3d p;
      if (!(fields >> p.x() >> p.y() >> p.z()))
        throw std::runtime_error(file.string() + ": bad vertex line: " + line);
      if (count < points_) x.col(count) = p;
      ++count;
    }
    if (count != points_)
      throw std::runtime_error(file.string() + " has " + std::to_string(count) +
                               " vertices, the cloth " + std::to_string(points_) + " particles");
    return x;
  }

 private:
  fs::path folder_;
  std::string solver_;
  int points_ = 0;
  int frames_ = 0;
};

// metrics.csv rows by solver and frame; only the columns the legend shows.
void read_metrics(const fs::path& file, std::vector<SolverFrames>& solvers) {
  const auto table = run_folder::read_csv_file(file);
  if (!table) return;  // legends without metrics
  const auto solver_column = table->column("solver"), frame_column = table->column("frame");
  const auto time_column = table->column("time"), stretch_column = table->column("max_stretch");
  const auto drape_column = table->column("drape_coefficient");
  if (!solver_column || !frame_column) return;
  using run_folder::parse_number;
  for (std::size_t r = 0; r < table->rows.size(); ++r) {
    for (auto& solver : solvers) {
      if (solver.name != table->text(r, solver_column)) continue;
      const auto frame = parse_number(table->text(r, frame_column));
      if (!frame) break;
      FrameMetrics metrics;
      metrics.time = parse_number(table->text(r, time_column)).value_or(0.0);
      metrics.max_stretch = parse_number(table->text(r, stretch_column));
      metrics.drape_coefficient = parse_number(table->text(r, drape_column));
      solver.metrics[static_cast<int>(*frame)] = metrics;
    }
  }
}

// bodies.csv rows by solver, frame and collider: each solver's own dynamic bodies.
void read_bodies(const fs::path& file, const scene::Scene& scene,
                 std::vector<SolverFrames>& solvers) {
  const auto table = run_folder::read_csv_file(file);
  if (!table) return;  // no dynamic colliders: they are drawn where the scene puts them
  const auto column = [&](const char* name) { return table->column(name); };
  const auto solver_column = column("solver"), frame_column = column("frame"),
             collider_column = column("collider");
  const std::array<std::optional<std::size_t>, 7> pose_columns = {
      column("x"),  column("y"),  column("z"), column("qx"),
      column("qy"), column("qz"), column("qw")};
  if (!solver_column || !frame_column || !collider_column) return;
  using run_folder::parse_number;
  for (std::size_t r = 0; r < table->rows.size(); ++r) {
    std::array<double, 7> value{};
    bool complete = true;
    for (std::size_t k = 0; k < value.size(); ++k) {
      const auto number =
          pose_columns[k] ? parse_number(table->text(r, pose_columns[k])) : std::nullopt;
      complete = complete && number.has_value();
      if (number) value[k] = *number;
    }
    const auto frame = parse_number(table->text(r, frame_column));
    int collider = -1;
    for (std::size_t c = 0; c < scene.colliders.size(); ++c)
      if (scene.colliders[c].name == table->text(r, collider_column))
        collider = static_cast<int>(c);
    if (!complete || !frame || collider < 0) continue;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(value[0], value[1], value[2]);
    pose.linear() =
        Eigen::Quaterniond(value[6], value[3], value[4], value[5]).normalized().toRotationMatrix();
    for (auto& solver : solvers)
      if (solver.name == table->text(r, solver_column))
        solver.bodies[static_cast<int>(*frame)][collider] = pose;
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
  if (!fs::is_directory(dir))
    throw RunInputError(dir.string() +
                        " is not a folder (give a run folder written by drapelab run)");
  const fs::path resolved = dir / "resolved.yaml", summary_file = dir / "summary.json";
  if (!fs::exists(resolved) || !fs::exists(summary_file))
    throw RunInputError(dir.string() +
                        " is not a run folder: it has no resolved.yaml or summary.json (write one "
                        "with drapelab run SCENE --out " +
                        dir.string() + " --meshes pc2)");
  // The run is done: a start inside a collider it was allowed (--allow-start-inside) is no error.
  auto loaded = scene::load_scene_file(resolved, {}, scene::StartInside::warning);
  if (!loaded.ok()) {
    std::string message = "the run's resolved.yaml does not load:";
    for (const auto& error : loaded.errors) message += "\n  " + error;
    throw RunInputError(message);
  }
  RunFrames run;
  run.dir = dir;
  run.scene = std::move(*loaded.scene);
  run.model = loaded.model ? *loaded.model : scene::build_scene_cloth(run.scene);

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
    if (entry.contains("frames_recorded") && entry["frames_recorded"].is_number_integer())
      solver.frames_recorded = entry["frames_recorded"].get<int>();
    const fs::path cache = meshes / run_folder::point_cache_name(name);
    if (fs::exists(cache))
      solver.source = open_point_cache(cache, run.model.particle_count());
    else if (fs::exists(meshes / run_folder::obj_frame_name(name, 0)))
      solver.source = open_obj_sequence(meshes, name, run.model.particle_count());
    else
      missing.push_back(name);
    run.solvers.push_back(std::move(solver));
  }
  if (run.solvers.empty()) throw RunInputError(summary_file.string() + " lists no solver");
  if (!missing.empty()) {
    std::string names;
    for (const auto& name : missing) names += (names.empty() ? "'" : ", '") + name + "'";
    throw RunInputError(dir.string() + " has no positions to draw for " + names +
                        ": neither a point cache (meshes/SOLVER.pc2) nor per-frame OBJ files "
                        "(meshes/SOLVER_NNNN.obj). "
                        "Run the scene again with them: drapelab run SCENE --out " +
                        dir.string() + " --meshes pc2 (or output.meshes: pc2 in the scene)");
  }
  for (const auto& solver : run.solvers) {
    // Fewer frames than the run recorded: the file lost frames after the run; drawing it would
    // silently draw fewer frames than the run has.
    if (solver.frames_recorded > solver.source->frame_count())
      throw RunInputError((meshes / solver.source->description()).string() + " holds " +
                          std::to_string(solver.source->frame_count()) + " frames, but " +
                          summary_file.string() + " says '" + solver.name + "' recorded " +
                          std::to_string(solver.frames_recorded) +
                          " (frame 0 included); the file is cut short. Run the scene again with "
                          "--meshes pc2");
    run.frame_count = std::max(run.frame_count, solver.source->frame_count());
  }
  if (run.frame_count == 0)
    throw RunInputError(dir.string() + ": the point caches hold no frame yet");
  read_metrics(dir / "metrics.csv", run.solvers);
  read_bodies(dir / "bodies.csv", run.scene, run.solvers);
  return run;
}

}  // namespace drapelab::render
