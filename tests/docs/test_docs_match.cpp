// The documentation's claims about the program, checked against the program:
//   - docs/outputs.md: the headers of compare.csv and contacts.csv as a run writes them;
//     compare.csv and contacts.csv written for every run, with their header alone when there
//     is no pair of solvers or no collider, and bodies.csv only with dynamic colliders;
//   - docs/outputs.md, "In Blender": the files the recipe names are the ones a run with
//     `--meshes both` writes, the frame-0 OBJ and the point cache hold the same vertices in the
//     same order, and the cache's first sample is frame 0 (hence the scene's start frame 0);
//   - docs/cli.md and `drapelab study --help`: the study's default runs every integrator, and
//     both say how many.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drapelab/integrators.hpp"
#include "drapelab/obj_reader.hpp"
#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/point_cache.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

namespace fs = std::filesystem;
using fixtures::read_text;
using fixtures::split_lines;

// A 9 x 9 sheet pinned at its corners, one solver, no collider, 0.1 s.
const std::string kOneSolver =
    "name: docs_small\n"
    "duration: 0.1\n"
    "seed: 7\n"
    "cloth:\n"
    "  size: [0.4, 0.4]\n"
    "  resolution: [9, 9]\n"
    "  mass: 0.1\n"
    "  perturbation: 0.001\n"
    "  springs:\n"
    "    stretch: {ks: 200, kd: 0.01}\n"
    "    shear: {ks: 20, kd: 0.005}\n"
    "    bend: {ks: 2, kd: 0.001}\n"
    "  pins:\n"
    "    - corners\n"
    "solvers:\n"
    "  - {name: ours, type: spring_damper, dt: 0.0010416666666666667}\n";

// The same sheet free, dropped onto a sphere by two solvers.
const std::string kTwoSolversOnASphere =
    "name: docs_sphere\n"
    "duration: 0.1\n"
    "seed: 7\n"
    "cloth:\n"
    "  size: [0.4, 0.4]\n"
    "  resolution: [9, 9]\n"
    "  plane: xz\n"
    "  center: [0, 0.21, 0]\n"
    "  mass: 0.1\n"
    "  springs:\n"
    "    stretch: {ks: 200, kd: 0.01}\n"
    "    shear: {ks: 20, kd: 0.005}\n"
    "    bend: {ks: 2, kd: 0.001}\n"
    "colliders:\n"
    "  - {name: ball, type: sphere, center: [0, 0, 0], radius: 0.2}\n"
    "solvers:\n"
    "  - {name: ours, type: spring_damper, dt: 0.0010416666666666667}\n"
    "  - {name: fine, type: spring_damper, dt: 0.00052083333333333333}\n";

fs::path source(const std::string& relative) { return fs::path(DRAPELAB_SOURCE_DIR) / relative; }

// The lines of the first ``` block after the heading `heading` of a Markdown file, joined (a long
// header is wrapped after its commas).
std::string code_block_after(const std::string& markdown, const std::string& heading) {
  const auto lines = split_lines(markdown);
  std::size_t k = 0;
  while (k < lines.size() && lines[k] != heading) ++k;
  while (k < lines.size() && lines[k].rfind("```", 0) != 0) ++k;
  std::string joined;
  for (++k; k < lines.size() && lines[k].rfind("```", 0) != 0; ++k) joined += lines[k];
  return joined;
}

// The row of a Markdown table that starts with `start`, or "".
std::string table_row(const std::string& markdown, const std::string& start) {
  for (const auto& line : split_lines(markdown))
    if (line.rfind(start, 0) == 0) return line;
  return "";
}

std::string joined_header(const fs::path& csv) {
  const auto table = run_folder::parse_csv(read_text(csv));
  std::string joined;
  for (const auto& cell : table.header) joined += (joined.empty() ? "" : ",") + cell;
  return joined;
}

class DocsMatch : public fixtures::TempDirTest {
 protected:
  // Runs `text` (with `overrides`) into dir()/NAME and returns the folder.
  fs::path run(const std::string& name, const std::string& text,
               const std::vector<std::string>& overrides = {}) {
    const fs::path file = dir() / (name + ".yaml");
    fixtures::write_text(file, text);
    const auto loaded = scene::load_scene_file(file, overrides);
    EXPECT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
    if (!loaded.ok()) return {};
    runner::RunOptions options;
    options.out_dir = dir() / name;
    options.scene_text = text;
    options.command_line = "test_docs_match";
    options.model = loaded.model;
    std::ostringstream log;
    const auto result = runner::run_scene(*loaded.scene, options, log);
    EXPECT_EQ(result.exit_code, runner::kExitOk) << log.str();
    return options.out_dir;
  }
};

TEST_F(DocsMatch, OutputsMdHasTheCompareAndContactsHeadersARunWrites) {
  const std::string outputs = read_text(source("docs/outputs.md"));
  const fs::path out = run("sphere", kTwoSolversOnASphere);
  for (const char* table : {run_folder::kCompareCsv, run_folder::kContactsCsv}) {
    SCOPED_TRACE(table);
    const std::string documented = code_block_after(outputs, std::string("## ") + table);
    ASSERT_FALSE(documented.empty()) << "docs/outputs.md has no header block for " << table;
    EXPECT_EQ(joined_header(out / table), documented);
    EXPECT_FALSE(run_folder::parse_csv(read_text(out / table)).rows.empty())
        << "two solvers on a sphere fill every table";
  }
  EXPECT_FALSE(fs::exists(out / "bodies.csv")) << "bodies.csv only with dynamic colliders";
}

// compare.csv and contacts.csv are part of every run folder; with nothing to hold, their header
// alone, as docs/outputs.md says in the table of files and in each table's section.
TEST_F(DocsMatch, CompareAndContactsCsvAreWrittenWithTheirHeaderAloneWhenEmpty) {
  const std::string outputs = read_text(source("docs/outputs.md"));
  const fs::path out = run("small", kOneSolver);
  for (const char* table : {run_folder::kCompareCsv, run_folder::kContactsCsv}) {
    SCOPED_TRACE(table);
    ASSERT_TRUE(fs::is_regular_file(out / table));
    const auto lines = split_lines(read_text(out / table));
    ASSERT_EQ(lines.size(), 1u) << "the header alone";
    EXPECT_EQ(lines[0], code_block_after(outputs, std::string("## ") + table));
    EXPECT_NE(table_row(outputs, std::string("| `") + table + "` |").find("header alone"),
              std::string::npos)
        << "the table of files says when " << table << " holds its header alone";
  }
  EXPECT_FALSE(fs::exists(out / "bodies.csv"));
  EXPECT_NE(table_row(outputs, "| `bodies.csv` |").find("only"), std::string::npos)
      << "the table of files says bodies.csv is written only with dynamic colliders";
}

// The PC2 header's start frame (float32 at byte 20: after "POINTCACHE2\0", the version and the
// point count).
float pc2_start_frame(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  char bytes[24] = {};
  file.read(bytes, sizeof bytes);
  float start = -1.0f;
  std::memcpy(&start, bytes + 20, sizeof start);
  return start;
}

TEST_F(DocsMatch, TheBlenderRecipesFilesHoldFrameZeroInParticleOrder) {
  const std::string outputs = read_text(source("docs/outputs.md"));
  const fs::path out = run("meshes", kOneSolver, {"output.meshes=both"});
  const fs::path meshes = out / run_folder::kMeshesFolder;
  const std::string obj = run_folder::obj_frame_name("ours", 0);
  const std::string pc2 = run_folder::point_cache_name("ours");
  // The recipe names these files and the option that writes both.
  EXPECT_NE(outputs.find("`meshes/" + obj + "`"), std::string::npos) << obj;
  EXPECT_NE(outputs.find("`meshes/" + pc2 + "`"), std::string::npos) << pc2;
  EXPECT_NE(outputs.find("--meshes both"), std::string::npos);

  const auto mesh = read_obj_file(meshes / obj);
  ASSERT_TRUE(mesh.mesh) << mesh.error;
  const auto header = run_folder::read_pc2_header(meshes / pc2);
  ASSERT_TRUE(header);
  const int points = static_cast<int>(mesh.mesh->vertices.cols());
  EXPECT_EQ(header->points, points) << "one cache point per OBJ vertex";
  EXPECT_EQ(header->samples, 7) << "frames 0 to 6";
  EXPECT_EQ(pc2_start_frame(meshes / pc2), 0.0f) << "the cache's first sample is frame 0";
  const auto first = run_folder::read_pc2_frame(meshes / pc2, points, 0);
  ASSERT_TRUE(first);
  // The same vertex k in both, in the same coordinates (the cache holds float32).
  EXPECT_LT((*first - mesh.mesh->vertices).cwiseAbs().maxCoeff(), 1e-6);
  const auto last = run_folder::read_pc2_frame(meshes / pc2, points, 6);
  ASSERT_TRUE(last);
  EXPECT_GT((*last - *first).cwiseAbs().maxCoeff(), 1e-3) << "the cloth moves";
}

std::string number_word(std::size_t n) {
  const char* words[] = {"zero", "one",   "two",   "three", "four", "five",
                         "six",  "seven", "eight", "nine",  "ten"};
  return n < 11 ? words[n] : std::to_string(n);
}

TEST_F(DocsMatch, StudysDefaultNamesHowManyIntegratorsItRuns) {
  const std::string all = "all " + number_word(all_integrators().size());
  const auto help = fixtures::run_drapelab({"study", "--help"});
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_NE(help.output.find("(default: " + all + ")"), std::string::npos) << help.output;
  const std::string cli = read_text(source("docs/cli.md"));
  const std::string row = table_row(cli, "| `--integrators a,b,...` |");
  EXPECT_NE(row.find("default: " + all + ","), std::string::npos) << row;
}

}  // namespace
}  // namespace drapelab
