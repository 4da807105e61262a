// Every scene shipped in scenes/*.yaml loads without error, starts with a comment saying what it
// shows, and its resolved form round-trips. The folder is listed at run time, so a new scene is
// covered as soon as it is added.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> scene_files() {
  std::vector<fs::path> files;
  const fs::path folder = fs::path(DRAPELAB_SOURCE_DIR) / "scenes";
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() &&
        (entry.path().extension() == ".yaml" || entry.path().extension() == ".yml"))
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += "\n  " + line;
  return text;
}

TEST(SceneFiles, TheRepositoryShipsScenes) {
  const auto files = scene_files();
  EXPECT_GE(files.size(), 3u)
      << "expected at least curtain, free_fall and hanging_chain in scenes/";
  for (const char* name : {"curtain.yaml", "free_fall.yaml", "hanging_chain.yaml"})
    EXPECT_NE(
        std::find(files.begin(), files.end(), fs::path(DRAPELAB_SOURCE_DIR) / "scenes" / name),
        files.end())
        << name;
}

TEST(SceneFiles, EverySceneLoadsWithoutError) {
  for (const auto& file : scene_files()) {
    SCOPED_TRACE(file.string());
    const auto result = drapelab::scene::load_scene_file(file);
    EXPECT_TRUE(result.ok()) << file << ":" << joined(result.errors);
  }
}

TEST(SceneFiles, EverySceneStartsWithAComment) {
  for (const auto& file : scene_files()) {
    const std::string text = read_text(file);
    const std::string first_line = text.substr(0, text.find('\n'));
    EXPECT_EQ(first_line.rfind("#", 0), 0u)
        << file << ": the first line should be a comment saying what the "
        << "scene shows, got [" << first_line << "]";
  }
}

TEST(SceneFiles, EverySceneResolvesToTextThatLoadsAgainUnchanged) {
  for (const auto& file : scene_files()) {
    SCOPED_TRACE(file.string());
    const auto first = drapelab::scene::load_scene_file(file);
    if (!first.ok()) continue;  // reported by EverySceneLoadsWithoutError
    const std::string written = drapelab::scene::resolved_scene_yaml(*first.scene);
    const auto second = drapelab::scene::load_scene_text(written, file.string());
    ASSERT_TRUE(second.ok()) << joined(second.errors) << "\nresolved text:\n" << written;
    EXPECT_EQ(drapelab::scene::resolved_scene_yaml(*second.scene), written);
  }
}

}  // namespace
