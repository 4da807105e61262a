// drapelab check: recording a golden file, passing against it, failing on a changed value with a
// readable report, refusing unstable runs, empty golden files and unwritable paths.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

using namespace fixtures;  // fixtures/cli.hpp

const char* kScene = R"(# a small cloth dropped on a sphere
name: check_me
duration: 0.5
frame_rate: 20
cloth: {resolution: [9, 9], size: [0.4, 0.4], center: [0, 0.5, 0], mass: 0.02,
        springs: {stretch: {ks: 200, kd: 0.01}, shear: {ks: 20, kd: 0.005}, bend: {ks: 1, kd: 0.001}}}
colliders:
  - {name: ball, type: sphere, center: [0, 0.3, 0], radius: 0.15}
contact: {stiffness: 500, damping: 0.05}
solvers: [{name: ours}]
)";

class CheckCli : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    scene_ = (dir() / "scene.yaml").string();
    golden_ = (dir() / "golden" / "scene.json").string();
    write_text(scene_, kScene);
  }
  std::string scene_, golden_;
};

TEST_F(CheckCli, RecordsAGoldenFileThenPassesAgainstIt) {
  const auto recorded =
      run_drapelab({"check", scene_, "--golden", golden_, "--update", "--set", "duration=0.4"});
  ASSERT_EQ(recorded.exit_code, 0) << recorded.output;
  EXPECT_NE(recorded.output.find("new golden file"), std::string::npos);
  const auto golden = nlohmann::json::parse(read_text(golden_));
  EXPECT_EQ(golden["scene"], "check_me");
  EXPECT_EQ(golden["overrides"][0], "duration=0.4");
  // Frame 0 and eight windows of a run of 8 frames: one frame each; metrics and the ball's
  // contacts for each, every value with a scale and a relative tolerance.
  ASSERT_EQ(golden["windows"].size(), 9u);
  EXPECT_TRUE(golden["windows"].contains("8"));
  EXPECT_TRUE(golden["windows"]["8"].contains("ours/ball"));
  EXPECT_GT(golden["windows"]["8"]["ours/ball"]["normal_force"].get<double>(), 0.0);
  EXPECT_GT(golden["scale"]["ours/ball"]["normal_force"].get<double>(), 0.0);
  EXPECT_GE(golden["relative"]["ours/ball"]["normal_force"].get<double>(), 0.005);

  const auto checked = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(checked.exit_code, 0) << checked.output;
  EXPECT_NE(checked.output.find("match"), std::string::npos) << checked.output;
  // Updating again changes nothing.
  const auto again =
      run_drapelab({"check", scene_, "--golden", golden_, "--update", "--set", "duration=0.4"});
  EXPECT_NE(again.output.find("no value changed"), std::string::npos) << again.output;
}

TEST_F(CheckCli, AChangedValueFailsWithARowColumnFrameReport) {
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  auto golden = nlohmann::json::parse(read_text(golden_));
  const double recorded = golden["windows"]["10"]["ours"]["centroid_y"].get<double>();
  const double tolerance = golden["scale"]["ours"]["centroid_y"].get<double>() *
                           golden["relative"]["ours"]["centroid_y"].get<double>();
  golden["windows"]["10"]["ours"]["centroid_y"] = recorded + 2 * tolerance;
  write_text(golden_, golden.dump(2));
  const auto checked = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(checked.exit_code, 1) << checked.output;
  EXPECT_NE(checked.output.find("1 of"), std::string::npos) << checked.output;
  EXPECT_NE(checked.output.find("frame 10 ours centroid_y"), std::string::npos) << checked.output;
  // Within the tolerance it passes: half of it.
  golden["windows"]["10"]["ours"]["centroid_y"] = recorded + 0.5 * tolerance;
  write_text(golden_, golden.dump(2));
  EXPECT_EQ(run_drapelab({"check", scene_, "--golden", golden_}).exit_code, 0);
}

// --first-difference: the run stops at the end of the first window that differs and the windows up
// to it are compared; with no difference the run goes on to its end and the check passes.
TEST_F(CheckCli, FirstDifferenceStopsAtTheEndOfTheFirstWindowThatDiffers) {
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  const auto unchanged = run_drapelab({"check", scene_, "--golden", golden_, "--first-difference"});
  EXPECT_EQ(unchanged.exit_code, 0) << unchanged.output;
  EXPECT_NE(unchanged.output.find("match"), std::string::npos) << unchanged.output;

  auto golden = nlohmann::json::parse(read_text(golden_));
  const double recorded = golden["windows"]["3"]["ours"]["centroid_y"].get<double>();
  const double tolerance = golden["scale"]["ours"]["centroid_y"].get<double>() *
                           golden["relative"]["ours"]["centroid_y"].get<double>();
  golden["windows"]["3"]["ours"]["centroid_y"] = recorded + 2 * tolerance;
  write_text(golden_, golden.dump(2));
  const std::string out = (dir() / "run").string();
  const auto checked =
      run_drapelab({"check", scene_, "--golden", golden_, "--first-difference", "--out", out});
  EXPECT_EQ(checked.exit_code, 1) << checked.output;
  EXPECT_NE(checked.output.find("stopped the run at frame 3"), std::string::npos) << checked.output;
  EXPECT_NE(checked.output.find("frame 3 ours centroid_y"), std::string::npos) << checked.output;
  EXPECT_NE(checked.output.find("values differ"), std::string::npos) << checked.output;
  // Frames 0 to 3 were run, of the scene's 10: the header and four rows.
  EXPECT_EQ(split_lines(read_text(std::filesystem::path(out) / "metrics.csv")).size(), 5u);
  // Without the flag the same check runs every frame and fails on the same value.
  const auto whole = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(whole.exit_code, 1) << whole.output;
  EXPECT_NE(whole.output.find("frame 3 ours centroid_y"), std::string::npos) << whole.output;
}

TEST_F(CheckCli, AChangedSceneIsCaught) {
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  std::string stiffer = kScene;
  stiffer.replace(stiffer.find("stiffness: 500"), 14, "stiffness: 900");
  write_text(scene_, stiffer);
  const auto checked = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(checked.exit_code, 1) << checked.output;
  EXPECT_NE(checked.output.find("max_penetration"), std::string::npos) << checked.output;
}

TEST_F(CheckCli, BadInputExitsWithTwo) {
  const auto missing = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("--update"), std::string::npos) << missing.output;
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  const auto bad_set = run_drapelab({"check", scene_, "--golden", golden_, "--set", "nokey=1"});
  EXPECT_EQ(bad_set.exit_code, 2) << bad_set.output;
  write_text(golden_, "{\"not\": \"a golden file\"}");
  const auto broken = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(broken.exit_code, 2);
  EXPECT_NE(broken.output.find("not a drapelab golden file"), std::string::npos) << broken.output;
}

TEST_F(CheckCli, SetWithoutUpdateGoesOnTopOfTheGoldenFilesOverrides) {
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  // 10 % stiffer contact: the penetration into the ball changes by about 9 %.
  const auto stiffer =
      run_drapelab({"check", scene_, "--golden", golden_, "--set", "contact.stiffness=550"});
  EXPECT_EQ(stiffer.exit_code, 1) << stiffer.output;
  EXPECT_NE(stiffer.output.find("extra override"), std::string::npos) << stiffer.output;
  EXPECT_NE(stiffer.output.find("max_penetration"), std::string::npos) << stiffer.output;
}

TEST_F(CheckCli, AGoldenFileThatComparesNothingIsBadInput) {
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  auto golden = nlohmann::json::parse(read_text(golden_));
  golden["windows"] = nlohmann::json::object();
  write_text(golden_, golden.dump(2));
  const auto checked = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(checked.exit_code, 2) << checked.output;
  EXPECT_NE(checked.output.find("compares nothing"), std::string::npos) << checked.output;
  // Windows without any value are as empty.
  golden["windows"] = {{"0", nlohmann::json::object()}};
  write_text(golden_, golden.dump(2));
  EXPECT_EQ(run_drapelab({"check", scene_, "--golden", golden_}).exit_code, 2);
}

TEST_F(CheckCli, UpdateRefusesAnUnstableRunAndLeavesTheOldFile) {
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  const std::string before = read_text(golden_);
  // Forward Euler at 10 ms on these springs blows up within the run.
  const auto unstable =
      run_drapelab({"check", scene_, "--golden", golden_, "--update", "--set",
                    "solvers.0.integrator=explicit_euler", "--set", "solvers.0.dt=0.01"});
  EXPECT_EQ(unstable.exit_code, 1) << unstable.output;
  EXPECT_NE(unstable.output.find("not recorded"), std::string::npos) << unstable.output;
  EXPECT_NE(unstable.output.find("ours: unstable"), std::string::npos) << unstable.output;
  EXPECT_EQ(read_text(golden_), before);
}

TEST_F(CheckCli, UpdateRefusesAFolderOrAnUnwritablePathBeforeRunning) {
  const auto folder = run_drapelab({"check", scene_, "--golden", dir().string(), "--update"});
  EXPECT_EQ(folder.exit_code, 2) << folder.output;
  EXPECT_NE(folder.output.find("is a folder"), std::string::npos) << folder.output;
  EXPECT_NE(folder.output.find("nothing was run"), std::string::npos) << folder.output;
  // A path under a file: its folder cannot exist.
  const std::string under_file = scene_ + "/golden.json";
  const auto unwritable = run_drapelab({"check", scene_, "--golden", under_file, "--update"});
  EXPECT_EQ(unwritable.exit_code, 2) << unwritable.output;
  EXPECT_NE(unwritable.output.find("cannot create the folder"), std::string::npos)
      << unwritable.output;
  // Checking against a folder is bad input too.
  EXPECT_EQ(run_drapelab({"check", scene_, "--golden", dir().string()}).exit_code, 2);
}

TEST_F(CheckCli, UpdateWritesThroughATemporaryFileAndLeavesNoneBehind) {
  ASSERT_EQ(run_drapelab({"check", scene_, "--golden", golden_, "--update"}).exit_code, 0);
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir() / "golden"))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"scene.json"});
}

}  // namespace
}  // namespace drapelab
