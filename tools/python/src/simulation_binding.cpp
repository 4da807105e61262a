// drapelab.load and drapelab.Simulation: a scene's solvers in memory, stepped from Python.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "bindings.hpp"
#include "drapelab/runner/metric_columns.hpp"
#include "drapelab/runner/simulation.hpp"
#include "interrupt_guard.hpp"
#include "run_binding.hpp"
#include "scene_source.hpp"

namespace py = pybind11;

namespace drapelab::python {
namespace {

// A 3 x N Eigen matrix as an (N, 3) array of its own.
template <typename Matrix>
py::array_t<typename Matrix::Scalar> rows_of_points(const Matrix& points) {
  using Scalar = typename Matrix::Scalar;
  py::array_t<Scalar> array({static_cast<py::ssize_t>(points.cols()), py::ssize_t{3}});
  auto out = array.template mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    for (int d = 0; d < 3; ++d) out(i, d) = points(d, i);
  return array;
}

py::array_t<double> vector3(const Eigen::Vector3d& v) {
  py::array_t<double> array(3);
  auto out = array.mutable_unchecked<1>();
  for (int d = 0; d < 3; ++d) out(d) = v[d];
  return array;
}

class PySimulation {
 public:
  PySimulation(LoadedScene loaded, std::vector<std::string> overrides)
      : scene_text_(std::move(loaded.text)), overrides_(std::move(overrides)) {
    const py::gil_scoped_release unlocked;  // building Bullet worlds and contact trees takes time
    simulation_ = std::make_unique<runner::Simulation>(*loaded.result.scene, loaded.result.model);
  }

  // The scene, the model and the solvers' names: fixed once built, read without the lock.
  const runner::Simulation& simulation() const { return *simulation_; }

  // The solvers' state, read while no other thread steps them: the lock is taken with the GIL
  // released (the stepping thread holds the lock without the GIL, so waiting for it with the GIL
  // would stall every Python thread), and held until the end of the full expression.
  class Locked {
   public:
    Locked(std::mutex& mutex, std::atomic<int>& waiting, const runner::Simulation& simulation)
        : lock_(mutex, std::defer_lock), simulation_(simulation) {
      if (lock_.try_lock()) return;
      ++waiting;  // the stepping thread lets a waiting reader in between two frames
      {
        const py::gil_scoped_release unlocked;
        lock_.lock();
      }
      --waiting;
    }
    const runner::Simulation* operator->() const { return &simulation_; }

   private:
    std::unique_lock<std::mutex> lock_;
    const runner::Simulation& simulation_;
  };
  Locked locked() const { return Locked(stepping_, readers_waiting_, *simulation_); }

  // Between two frames: a reader waiting for the lock takes it before the next frame does (a
  // mutex taken again at once would starve it).
  void let_readers_in() const {
    while (readers_waiting_.load() > 0) std::this_thread::yield();
  }

  // A solver named by its name or its index in the scene's list.
  std::size_t solver_index(const py::object& solver) const {
    if (py::isinstance<py::int_>(solver)) {
      const auto index = py::cast<long long>(solver);
      if (index < 0 || static_cast<std::size_t>(index) >= simulation_->solver_count())
        throw py::index_error("solver index " + std::to_string(index) +
                              " is out of range: the scene has " +
                              std::to_string(simulation_->solver_count()) + " solvers");
      return static_cast<std::size_t>(index);
    }
    const auto name = py::cast<std::string>(solver);
    if (const auto index = simulation_->find_solver(name)) return *index;
    std::string names;
    for (std::size_t k = 0; k < simulation_->solver_count(); ++k)
      names += (k ? ", " : "") + simulation_->solver_name(k);
    throw py::key_error("no solver named '" + name + "'; the scene's solvers are " + names);
  }

  std::vector<std::size_t> chosen(const py::object& solver) const {
    std::vector<std::size_t> indices;
    if (solver.is_none())
      for (std::size_t k = 0; k < simulation_->solver_count(); ++k) indices.push_back(k);
    else
      indices.push_back(solver_index(solver));
    return indices;
  }

  // Steps the chosen solvers frame by frame in lock-step, the GIL released.
  void step(int frames, const py::object& solver) {
    if (frames < 0) throw py::value_error("frames must be >= 0, got " + std::to_string(frames));
    const std::vector<std::size_t> indices = chosen(solver);
    const InterruptGuard guard;
    {
      const py::gil_scoped_release unlocked;
      for (int f = 0; f < frames; ++f) {
        if (guard.flag() && guard.flag()->load()) break;
        let_readers_in();
        const std::lock_guard<std::mutex> lock(stepping_);  // a frame at a time: reads go between
        for (const std::size_t k : indices) simulation_->advance(k, 1, guard.flag());
      }
    }
    guard.raise_if_interrupted();
  }

  // Steps the chosen solvers through the scene's duration (those past it stay).
  void step_to_end(const py::object& solver) {
    const std::vector<std::size_t> indices = chosen(solver);
    const InterruptGuard guard;
    {
      const py::gil_scoped_release unlocked;
      const int last = simulation_->scene().frame_count();
      for (int frame = 1; frame <= last; ++frame) {
        if (guard.flag() && guard.flag()->load()) break;
        let_readers_in();
        const std::lock_guard<std::mutex> lock(stepping_);
        for (const std::size_t k : indices)
          if (simulation_->frame(k) < frame) simulation_->advance(k, 1, guard.flag());
      }
    }
    guard.raise_if_interrupted();
  }

  // Every measured frame of a solver: frame, time, then metrics.csv's columns.
  py::dict metrics(const py::object& solver) const {
    const Locked simulation = locked();
    const auto& records = simulation->records(solver_index(solver));
    const auto count = static_cast<py::ssize_t>(records.size());
    py::dict columns;
    py::array_t<std::int64_t> frames(count);
    py::array_t<double> times(count);
    for (py::ssize_t k = 0; k < count; ++k) {
      frames.mutable_at(k) = records[static_cast<std::size_t>(k)].frame;
      times.mutable_at(k) = records[static_cast<std::size_t>(k)].time;
    }
    columns["frame"] = frames;
    columns["time"] = times;
    for (const runner::MetricColumn& column : runner::metric_columns()) {
      py::array_t<double> values(count);
      for (py::ssize_t k = 0; k < count; ++k)
        values.mutable_at(k) = column.value(records[static_cast<std::size_t>(k)].metrics)
                                   .value_or(std::numeric_limits<double>::quiet_NaN());
      columns[py::str(column.name)] = values;
    }
    return columns;
  }

  py::dict bodies(const py::object& solver) const {
    py::dict bodies;
    for (const BodyState& body : locked()->bodies(solver_index(solver))) {
      const Eigen::Quaterniond q(body.pose.rotation());
      py::array_t<double> orientation(4);
      orientation.mutable_at(0) = q.x();
      orientation.mutable_at(1) = q.y();
      orientation.mutable_at(2) = q.z();
      orientation.mutable_at(3) = q.w();
      py::dict entry;
      entry["position"] = vector3(body.pose.translation());
      entry["orientation"] = orientation;
      entry["velocity"] = vector3(body.velocity);
      entry["angular_velocity"] = vector3(body.angular_velocity);
      bodies[py::str(
          simulation_->scene().colliders[static_cast<std::size_t>(body.collider)].name)] = entry;
    }
    return bodies;
  }

  py::object run(const std::string& out, bool force) const {
    return run_into_folder(simulation_->scene(), scene_text_, overrides_, out, force);
  }

  std::string repr() const {
    const Locked simulation = locked();
    std::ostringstream text;
    text << "<drapelab.Simulation '" << simulation->scene().name << "':";
    for (std::size_t k = 0; k < simulation->solver_count(); ++k)
      text << (k ? "," : "") << " " << simulation->solver_name(k) << " frame "
           << simulation->frame(k) << " (" << solver_status_name(simulation->status(k)) << ")";
    text << ">";
    return text.str();
  }

 private:
  std::string scene_text_;
  std::vector<std::string> overrides_;
  std::unique_ptr<runner::Simulation> simulation_;
  mutable std::mutex stepping_;  // held while a thread steps the solvers through a frame
  mutable std::atomic<int> readers_waiting_{0};
};

}  // namespace

void bind_simulation(py::module_& module) {
  std::vector<std::string> metric_names{"frame", "time"};
  for (const auto& column : runner::metric_columns()) metric_names.push_back(column.name);
  module.attr("METRICS") = py::cast(metric_names);

  py::class_<PySimulation>(module, "Simulation",
                           "A scene's solvers in memory, stepped frame by frame (drapelab.load).")
      .def_property_readonly("name",
                             [](const PySimulation& s) { return s.simulation().scene().name; })
      .def_property_readonly(
          "solvers",
          [](const PySimulation& s) {
            std::vector<std::string> names;
            for (std::size_t k = 0; k < s.simulation().solver_count(); ++k)
              names.push_back(s.simulation().solver_name(k));
            return names;
          },
          "The solvers' names, in the scene's order.")
      .def_property_readonly(
          "frame_rate", [](const PySimulation& s) { return s.simulation().scene().frame_rate; },
          "Frames per simulated second.")
      .def_property_readonly(
          "duration", [](const PySimulation& s) { return s.simulation().scene().duration; },
          "The scene's duration (s); step() may go past it.")
      .def_property_readonly(
          "frame_count", [](const PySimulation& s) { return s.simulation().scene().frame_count(); },
          "The scene's last frame.")
      .def_property_readonly(
          "particle_count",
          [](const PySimulation& s) { return s.simulation().model().particle_count(); })
      .def_property_readonly(
          "triangles",
          [](const PySimulation& s) { return rows_of_points(s.simulation().model().triangles); },
          "(T, 3) int array: each triangle's particle indices.")
      .def_property_readonly(
          "rest_positions",
          [](const PySimulation& s) {
            return rows_of_points(s.simulation().model().rest_positions);
          },
          "(N, 3) array, m: the cloth as built, before the scene's perturbation.")
      .def("step", &PySimulation::step, py::arg("frames") = 1, py::arg("solver") = py::none(),
           "Steps every solver (or the one named) through `frames` more frames, in lock-step, "
           "each frame measured as drapelab run measures it. A solver that stops (unstable) stays "
           "stopped: see status() and message(). The GIL is released meanwhile; Ctrl-C stops after "
           "the current step and raises KeyboardInterrupt.")
      .def("step_to_end", &PySimulation::step_to_end, py::arg("solver") = py::none(),
           "Steps every solver (or the one named) through the scene's duration.")
      .def(
          "frame",
          [](const PySimulation& s, const py::object& solver) {
            return s.locked()->frame(s.solver_index(solver));
          },
          py::arg("solver"), "The solver's last measured frame (0: the initial state).")
      .def(
          "time",
          [](const PySimulation& s, const py::object& solver) {
            return s.locked()->time(s.solver_index(solver));
          },
          py::arg("solver"), "The simulated time of that frame (s).")
      .def(
          "status",
          [](const PySimulation& s, const py::object& solver) {
            return std::string(solver_status_name(s.locked()->status(s.solver_index(solver))));
          },
          py::arg("solver"), "'ok', 'unstable' or 'error'.")
      .def(
          "message",
          [](const PySimulation& s, const py::object& solver) {
            return s.locked()->message(s.solver_index(solver));
          },
          py::arg("solver"), "Why the solver stopped (which particle, which step, what to try).")
      .def(
          "positions",
          [](const PySimulation& s, const py::object& solver) {
            return rows_of_points(s.locked()->state(s.solver_index(solver)).x);
          },
          py::arg("solver"), "(N, 3) array of the particles' positions, m (a copy).")
      .def(
          "velocities",
          [](const PySimulation& s, const py::object& solver) {
            return rows_of_points(s.locked()->state(s.solver_index(solver)).v);
          },
          py::arg("solver"), "(N, 3) array of the particles' velocities, m/s (a copy).")
      .def("metrics", &PySimulation::metrics, py::arg("solver"),
           "Every frame measured so far: a dict of arrays, one per name of drapelab.METRICS "
           "(frame, time, then metrics.csv's columns; NaN where metrics.csv leaves a cell empty).")
      .def("bodies", &PySimulation::bodies, py::arg("solver"),
           "The solver's copies of the scene's dynamic colliders: {name: {position, orientation "
           "(x, y, z, w), velocity, angular_velocity}}.")
      .def(
          "steps",
          [](const PySimulation& s, const py::object& solver) {
            return s.locked()->steps(s.solver_index(solver));
          },
          py::arg("solver"))
      .def(
          "wall_seconds",
          [](const PySimulation& s, const py::object& solver) {
            return s.locked()->wall_seconds(s.solver_index(solver));
          },
          py::arg("solver"), "Wall-clock seconds spent stepping the solver.")
      .def("run", &PySimulation::run, py::arg("out"), py::kw_only(), py::arg("force") = false,
           "Runs the scene from its start into the run folder `out`, exactly as drapelab run does "
           "(this simulation's state is not used); returns drapelab.read_run(out).")
      .def("__repr__", &PySimulation::repr);

  module.def(
      "load",
      [](const py::object& scene, const py::object& overrides) {
        std::vector<std::string> texts = override_texts(overrides);
        LoadedScene loaded = load_scene(scene, texts);
        return std::make_unique<PySimulation>(std::move(loaded), std::move(texts));
      },
      py::arg("scene"), py::arg("overrides") = py::none(),
      "Loads a scene (a file path or a dict of the scene file's keys) with `overrides` "
      "({'key.path': "
      "value} or ['key.path=value', ...], as drapelab run --set), and builds its solvers at frame "
      "0. Raises drapelab.SceneError naming the file, line and key of every problem.");
}

}  // namespace drapelab::python
