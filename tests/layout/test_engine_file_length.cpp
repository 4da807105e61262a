// No source or header of the engine is longer than 400 lines (docs/testing.md, "Engine layers"):
// a longer file holds more than one topic and is split by topic, each part named for what it
// holds. The test names every file over the limit and its line count.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr int kMostLines = 400;

fs::path engine_dir() { return fs::path(DRAPELAB_SOURCE_DIR) / "engine"; }

// Lines as `wc -l` counts them, plus a last line without its newline.
int line_count(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  return lines;
}

TEST(EngineFileLength, NoSourceOrHeaderIsLongerThanTheLimit) {
  std::vector<std::pair<std::string, int>> too_long;  // engine-relative path, lines
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(engine_dir())) {
    const fs::path& path = entry.path();
    if (!entry.is_regular_file() || (path.extension() != ".cpp" && path.extension() != ".hpp"))
      continue;
    ++files;
    const int lines = line_count(path);
    if (lines > kMostLines)
      too_long.emplace_back((fs::path("engine") / fs::relative(path, engine_dir())).string(),
                            lines);
  }
  ASSERT_GT(files, 50) << "the scan found too few files to be reading the engine";
  std::sort(too_long.begin(), too_long.end());
  for (const auto& [file, lines] : too_long)
    ADD_FAILURE() << file << " has " << lines << " lines, more than " << kMostLines
                  << ": split it by topic";
}

}  // namespace
