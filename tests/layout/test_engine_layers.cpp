// The engine's folders form layers (docs/testing.md, "Engine layers"): a file may include headers
// of its own folder or of a folder on a lower floor, never of a folder on its own floor or above,
// so the include graph between folders has no cycle. The floors, lowest first:
//   core                                               closest points, the penalty law, thread
//   blocks cloth                                              the cloth model and its builders
//   forces, air, constraints, contact, self_collision  one topic each
//   integrators, metrics                               the step and the measures, over the topics
// The public headers (include/drapelab) are what the rest of the program sees: they include no
// private header, so the runner, bullet_bridge and the viewer depend on no folder's inside.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::map<std::string, int> kFloor = {
    {"core", 0},    {"cloth", 1},          {"forces", 2},      {"air", 2},    {"constraints", 2},
    {"contact", 2}, {"self_collision", 2}, {"integrators", 3}, {"metrics", 3}};

struct Include {
  std::string from_folder, to_folder;
  std::string where;  // file:line
};

fs::path engine_dir() { return fs::path(DRAPELAB_SOURCE_DIR) / "engine"; }

// Every `#include "folder/..."` of a private engine header in the engine's sources.
std::vector<Include> engine_includes() {
  const std::regex include_line(R"re(^\s*#\s*include\s*"([a-z_]+)/)re");
  std::vector<Include> found;
  for (const auto& entry : fs::recursive_directory_iterator(engine_dir())) {
    const fs::path& path = entry.path();
    if (path.extension() != ".cpp" && path.extension() != ".hpp") continue;
    const fs::path relative = fs::relative(path, engine_dir());
    const std::string folder = relative.begin()->string();
    std::ifstream in(path);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      std::smatch match;
      if (!std::regex_search(line, match, include_line)) continue;
      if (!kFloor.count(match[1].str())) continue;  // "drapelab/...": a public header
      found.push_back({folder, match[1].str(), relative.string() + ":" + std::to_string(number)});
    }
  }
  return found;
}

TEST(EngineLayers, EveryFolderHasAFloor) {
  for (const auto& entry : fs::directory_iterator(engine_dir())) {
    if (!entry.is_directory()) continue;
    const std::string folder = entry.path().filename().string();
    if (folder == "include") continue;
    EXPECT_TRUE(kFloor.count(folder))
        << "engine/" << folder << " has no floor in this test's table: add it";
  }
}

TEST(EngineLayers, IncludesGoDownTheFloorsOnly) {
  const std::vector<Include> includes = engine_includes();
  ASSERT_GT(includes.size(), 50u) << "the scan found too few includes to be reading the engine";
  for (const Include& include : includes) {
    if (include.from_folder == include.to_folder) continue;
    ASSERT_TRUE(kFloor.count(include.from_folder) || include.from_folder == "include")
        << include.where;
    EXPECT_NE(include.from_folder, "include")
        << include.where << ": a public header includes the private " << include.to_folder
        << "/ (the rest of the program must see only include/drapelab)";
    if (include.from_folder == "include") continue;
    EXPECT_LT(kFloor.at(include.to_folder), kFloor.at(include.from_folder))
        << include.where << ": " << include.from_folder << "/ (floor "
        << kFloor.at(include.from_folder) << ") includes " << include.to_folder << "/ (floor "
        << kFloor.at(include.to_folder) << "); a folder may include only lower floors";
  }
}

TEST(EngineLayers, TheFolderGraphHasNoCycle) {
  std::map<std::string, std::set<std::string>> edges;
  for (const Include& include : engine_includes())
    if (include.from_folder != include.to_folder)
      edges[include.from_folder].insert(include.to_folder);
  // Depth-first search: a folder met again while still on the path closes a cycle.
  std::map<std::string, int> state;  // 0 unseen, 1 on the path, 2 done
  std::vector<std::string> path;
  const std::function<void(const std::string&)> visit = [&](const std::string& folder) {
    state[folder] = 1;
    path.push_back(folder);
    for (const std::string& next : edges[folder]) {
      if (state[next] == 1) {
        std::string cycle;
        for (const std::string& step : path) cycle += step + " -> ";
        ADD_FAILURE() << "include cycle: " << cycle << next;
      } else if (state[next] == 0) {
        visit(next);
      }
    }
    path.pop_back();
    state[folder] = 2;
  };
  for (const auto& [folder, targets] : edges)
    if (state[folder] == 0) visit(folder);
}

}  // namespace
