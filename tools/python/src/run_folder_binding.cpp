// drapelab.run, read_run, read_sweep and read_csv: run folders and sweep folders from Python, their
// tables as dicts of NumPy arrays and their JSON files as dicts.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"
#include "numpy_tables.hpp"
#include "run_binding.hpp"
#include "scene_source.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace drapelab::python {
namespace {

[[noreturn]] void raise_missing(const fs::path& file, const std::string& what) {
  PyErr_SetString(PyExc_FileNotFoundError, (file.string() + ": " + what).c_str());
  throw py::error_already_set();
}

run_folder::CsvTable read_table(const fs::path& file) {
  auto table = run_folder::read_csv_file(file);
  if (!table) raise_missing(file, "no such table (or it cannot be read)");
  return std::move(*table);
}

py::object read_json(const fs::path& file) {
  const auto text = run_folder::read_file_bytes(file);
  if (!text) raise_missing(file, "no such file (or it cannot be read)");
  return py::module_::import("json").attr("loads")(*text);
}

// A folder's path from a str or os.PathLike.
std::string folder_path(const py::object& folder) {
  return py::cast<std::string>(py::module_::import("os").attr("fspath")(folder));
}

// A run folder (drapelab run, drapelab.run): its files read on demand.
class RunFolder {
 public:
  explicit RunFolder(fs::path path) : path_(std::move(path)) {
    if (!fs::is_regular_file(path_ / "summary.json"))
      raise_missing(path_ / "summary.json", "not a run folder (drapelab run writes summary.json)");
  }
  std::string path() const { return path_.string(); }
  py::object summary() const { return read_json(path_ / "summary.json"); }

  // The names of the folder's tables (metrics, compare, contacts, bodies...), sorted.
  std::vector<std::string> tables() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_))
      if (entry.path().extension() == ".csv") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  // A table's rows, all or those of one solver (a table with a solver column).
  py::dict table(const std::string& name, const py::object& solver) const {
    const run_folder::CsvTable table = read_table(path_ / (name + ".csv"));
    if (solver.is_none()) return table_arrays(table);
    const auto column = table.column("solver");
    if (!column) throw py::value_error(name + ".csv has no solver column");
    const auto wanted = py::cast<std::string>(solver);
    std::vector<std::size_t> rows;
    for (std::size_t r = 0; r < table.rows.size(); ++r)
      if (table.text(r, column) == wanted) rows.push_back(r);
    if (rows.empty())
      throw py::key_error(name + ".csv has no rows of a solver named '" + wanted + "'");
    return table_arrays(table, rows);
  }

  std::vector<std::string> solvers() const {
    // summary.json's "solvers" maps each name to its results, in the run's order.
    const py::object whole = summary();
    const py::dict by_name = whole["solvers"];
    std::vector<std::string> names;
    for (const auto& entry : by_name) names.push_back(py::cast<std::string>(entry.first));
    return names;
  }

 private:
  fs::path path_;
};

// A sweep folder (drapelab sweep): sweep.csv, sweep.json and its run folders.
class SweepFolder {
 public:
  explicit SweepFolder(fs::path path) : path_(std::move(path)) {
    if (!fs::is_regular_file(path_ / "sweep.csv"))
      raise_missing(path_ / "sweep.csv", "not a sweep folder (drapelab sweep writes sweep.csv)");
  }
  std::string path() const { return path_.string(); }
  py::dict table() const { return table_arrays(read_table(path_ / "sweep.csv")); }
  py::object record() const { return read_json(path_ / "sweep.json"); }
  // Every run folder the sweep wrote, in combination order.
  std::vector<RunFolder> runs() const {
    const run_folder::CsvTable table = read_table(path_ / "sweep.csv");
    const auto column = table.column("run_folder");
    std::vector<std::string> seen;
    std::vector<RunFolder> runs;
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
      const std::string& folder = table.text(r, column);
      if (folder.empty() || std::find(seen.begin(), seen.end(), folder) != seen.end()) continue;
      seen.push_back(folder);
      if (fs::is_regular_file(path_ / folder / "summary.json")) runs.emplace_back(path_ / folder);
    }
    return runs;
  }

 private:
  fs::path path_;
};

}  // namespace

py::object open_run_folder(const std::string& folder) { return py::cast(RunFolder(folder)); }

void bind_run_folders(py::module_& module) {
  py::class_<RunFolder>(module, "RunFolder",
                        "A run folder written by drapelab run or drapelab.run.")
      .def_property_readonly("path", &RunFolder::path)
      .def_property_readonly("summary", &RunFolder::summary, "summary.json as a dict.")
      .def_property_readonly("solvers", &RunFolder::solvers,
                             "The solvers' names, in the run's order.")
      .def_property_readonly("tables", &RunFolder::tables, "The names of the folder's CSV tables.")
      .def("table", &RunFolder::table, py::arg("name"), py::arg("solver") = py::none(),
           "A table (metrics, compare, contacts, bodies...) as a dict of arrays, every row or one "
           "solver's.")
      .def(
          "metrics",
          [](const RunFolder& run, const py::object& solver) {
            return run.table("metrics", solver);
          },
          py::arg("solver") = py::none(),
          "metrics.csv as a dict of arrays, every row or one solver's.")
      .def("__repr__",
           [](const RunFolder& run) { return "<drapelab.RunFolder '" + run.path() + "'>"; })
      .def("__fspath__", &RunFolder::path);

  py::class_<SweepFolder>(module, "SweepFolder", "A sweep folder written by drapelab sweep.")
      .def_property_readonly("path", &SweepFolder::path)
      .def_property_readonly("table", &SweepFolder::table,
                             "sweep.csv as a dict of arrays (one row per combination and solver).")
      .def_property_readonly("record", &SweepFolder::record, "sweep.json as a dict.")
      .def_property_readonly("runs", &SweepFolder::runs, "The sweep's run folders.")
      .def("__repr__",
           [](const SweepFolder& sweep) { return "<drapelab.SweepFolder '" + sweep.path() + "'>"; })
      .def("__fspath__", &SweepFolder::path);

  module.def(
      "run",
      [](const py::object& scene, const py::object& out, const py::object& overrides, bool force) {
        const std::vector<std::string> texts = override_texts(overrides);
        const LoadedScene loaded = load_scene(scene, texts);
        return run_into_folder(*loaded.result.scene, loaded.text, texts, folder_path(out), force);
      },
      py::arg("scene"), py::arg("out"), py::arg("overrides") = py::none(), py::kw_only(),
      py::arg("force") = false,
      "Runs a scene (a path or a dict, with overrides as drapelab.load takes them) into the run "
      "folder `out`, exactly as drapelab run does, and returns it as a RunFolder. force=True "
      "replaces a previous run there.");
  module.def(
      "read_run", [](const py::object& folder) { return RunFolder(folder_path(folder)); },
      py::arg("folder"), "A run folder's files (summary.json, metrics.csv, ...).");
  module.def(
      "read_sweep", [](const py::object& folder) { return SweepFolder(folder_path(folder)); },
      py::arg("folder"), "A sweep folder's files (sweep.csv, sweep.json, runs/).");
  module.def(
      "read_csv",
      [](const py::object& file) { return table_arrays(read_table(folder_path(file))); },
      py::arg("file"),
      "Any CSV table of drapelab's as a dict of arrays: int64 for whole-number columns, float64 "
      "for numbers (NaN for empty cells), str otherwise.");
}

}  // namespace drapelab::python
