// drapelab check: recording a golden file, passing against it, failing on a changed value with a
// readable report, and refusing bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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
  // Five frames of a run of 8: 0, 2, 4, 6, 8; metrics and the ball's contacts for each.
  ASSERT_EQ(golden["frames"].size(), 5u);
  EXPECT_TRUE(golden["frames"].contains("8"));
  EXPECT_TRUE(golden["frames"]["8"].contains("ours/ball"));
  EXPECT_GT(golden["frames"]["8"]["ours/ball"]["normal_force"].get<double>(), 0.0);

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
  const double recorded = golden["frames"]["10"]["ours"]["centroid_y"].get<double>();
  golden["frames"]["10"]["ours"]["centroid_y"] = recorded + 0.01;  // far beyond the tolerance
  write_text(golden_, golden.dump(2));
  const auto checked = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(checked.exit_code, 1) << checked.output;
  EXPECT_NE(checked.output.find("1 of"), std::string::npos) << checked.output;
  EXPECT_NE(checked.output.find("frame 10 ours centroid_y"), std::string::npos) << checked.output;
  // Within the tolerance it passes: a relative change of 1e-6 against 1e-4 allowed.
  golden["frames"]["10"]["ours"]["centroid_y"] = recorded * (1 + 1e-6);
  write_text(golden_, golden.dump(2));
  EXPECT_EQ(run_drapelab({"check", scene_, "--golden", golden_}).exit_code, 0);
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
  const auto with_set = run_drapelab({"check", scene_, "--golden", golden_, "--set", "duration=1"});
  EXPECT_EQ(with_set.exit_code, 2);
  write_text(golden_, "{\"not\": \"a golden file\"}");
  const auto broken = run_drapelab({"check", scene_, "--golden", golden_});
  EXPECT_EQ(broken.exit_code, 2);
  EXPECT_NE(broken.output.find("not a drapelab golden file"), std::string::npos) << broken.output;
}

}  // namespace
}  // namespace drapelab
