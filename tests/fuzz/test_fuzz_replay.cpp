// Replays every input of the fuzz corpus and every saved crash (tests/fuzz/corpus/, crashes/)
// through the fuzz targets' entry points, without libFuzzer: the regular build and the sanitizer
// build catch a regression on any of them. One test per file, named after it.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_inputs.hpp"

namespace drapelab::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(DRAPELAB_SOURCE_DIR) / "tests" / "fuzz";

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
constexpr bool kAddressSanitizer = __has_feature(address_sanitizer);
#else
constexpr bool kAddressSanitizer = false;
#endif

// An input whose memory grows without end fails its test instead of exhausting the machine: 4 GB
// of address space at most, so the allocation fails. AddressSanitizer reserves terabytes of address
// space; there a hard RSS limit does the same (asan_defaults.cpp).
[[maybe_unused]] const bool kMemoryBounded = [] {
  if (kAddressSanitizer) return false;
  const rlimit limit{rlim_t{4} << 30, rlim_t{4} << 30};
  return setrlimit(RLIMIT_AS, &limit) == 0;
}();

struct ReplayFile {
  std::string target;  // "scene" or "obj": the entry point and the subfolder
  fs::path path;
};

// Every file under corpus/TARGET/ and crashes/TARGET/, sorted so test names are stable.
std::vector<ReplayFile> replay_files() {
  std::vector<ReplayFile> files;
  for (const std::string target : {"scene", "obj"})
    for (const std::string folder : {"corpus", "crashes"})
      if (fs::is_directory(kFuzzDir / folder / target))
        for (const auto& entry : fs::directory_iterator(kFuzzDir / folder / target))
          if (entry.is_regular_file()) files.push_back({target, entry.path()});
  std::sort(files.begin(), files.end(),
            [](const ReplayFile& a, const ReplayFile& b) { return a.path < b.path; });
  return files;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// "corpus_scene_0a1b..." or "crashes_obj_long_name": letters, digits and _ only (GoogleTest names).
std::string test_name(const ReplayFile& file) {
  std::string name = file.path.parent_path().parent_path().filename().string() + "_" + file.target +
                     "_" + file.path.filename().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

// How CTest shows the parameter: the file, from tests/fuzz/.
void PrintTo(const ReplayFile& file, std::ostream* out) {
  *out << file.path.lexically_relative(kFuzzDir).string();
}

class Replay : public ::testing::TestWithParam<ReplayFile> {};

TEST_P(Replay, KeepsEveryProperty) {
  const ReplayFile& file = GetParam();
  ASSERT_TRUE(fs::is_regular_file(file.path)) << file.path;
  const std::string data = read_bytes(file.path);
  const auto broken = file.target == "scene" ? load_scene_input(data) : read_obj_input(data);
  EXPECT_FALSE(broken.has_value()) << file.path.string() << ": " << broken.value_or("");
}

INSTANTIATE_TEST_SUITE_P(Fuzz, Replay, ::testing::ValuesIn(replay_files()),
                         [](const auto& test) { return test_name(test.param); });

// The corpus is what the CI fuzz runs start from and what this test replays: it must not vanish.
TEST(FuzzCorpus, HoldsScenesAndObjFiles) {
  const auto files = replay_files();
  const auto count = [&](const std::string& target) {
    return std::count_if(files.begin(), files.end(),
                         [&](const ReplayFile& f) { return f.target == target; });
  };
  EXPECT_GE(count("scene"), 10);
  EXPECT_GE(count("obj"), 5);
}

// The override section of a scene input: NUL-separated pieces after the text, at most
// kMaxOverrides.
TEST(FuzzSceneInput, SplitsTextAndOverridesAtNulBytes) {
  using namespace std::string_literals;
  const SceneInput plain = split_scene_input("name: a\n");
  EXPECT_EQ(plain.text, "name: a\n");
  EXPECT_TRUE(plain.overrides.empty());
  const SceneInput with = split_scene_input("name: a\n\0seed=3\0\0cloth.mass=1"s);
  EXPECT_EQ(with.text, "name: a\n");
  EXPECT_EQ(with.overrides, (std::vector<std::string>{"seed=3", "", "cloth.mass=1"}));
  const SceneInput many = split_scene_input(std::string(20, '\0'));
  EXPECT_EQ(many.overrides.size(), kMaxOverrides);
}

}  // namespace
}  // namespace drapelab::fuzz
