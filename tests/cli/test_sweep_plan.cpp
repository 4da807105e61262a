// The parts of `drapelab sweep` on their own: splitting --vary values, the combination order,
// folder names, and telling a misspelt key from a bad value in the scene loader's errors.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/sweep/plan.hpp"
#include "drapelab/sweep/validation.hpp"
#include "fixtures/sweep_scene.hpp"

namespace {

using drapelab::fixtures::kSweepSheet;

TEST(SweepPlan, SplitsValuesOnCommasOutsideBracketsAndQuotes) {
  std::string error;
  using List = std::vector<std::string>;
  EXPECT_EQ(drapelab::sweep::split_values("1, 10,100", &error).value_or(List{}),
            (List{"1", "10", "100"}));
  EXPECT_EQ(drapelab::sweep::split_values("[5,5],[7,7]", &error).value_or(List{}),
            (List{"[5,5]", "[7,7]"}));
  EXPECT_EQ(drapelab::sweep::split_values("{ks: 1, kd: 0},[1,[2,3]]", &error).value_or(List{}),
            (List{"{ks: 1, kd: 0}", "[1,[2,3]]"}));
  EXPECT_EQ(drapelab::sweep::split_values("'a,b',\"c,d\"", &error).value_or(List{}),
            (List{"'a,b'", "\"c,d\""}));
  for (const std::string bad : {"[5,5", "5]", "1,,2", "1,", "", "'open"}) {
    EXPECT_FALSE(drapelab::sweep::split_values(bad, &error)) << bad;
    EXPECT_FALSE(error.empty());
  }
  const auto varied = drapelab::sweep::parse_vary("cloth.resolution=[5,5],[7,7]", &error);
  ASSERT_TRUE(varied) << error;
  EXPECT_EQ(varied->key, "cloth.resolution");
  EXPECT_EQ(varied->values, (List{"[5,5]", "[7,7]"}));
  for (const std::string bad : {"no_equals", "=1,2", "a..b=1", ".a=1"})
    EXPECT_FALSE(drapelab::sweep::parse_vary(bad, &error)) << bad;
}

TEST(SweepPlan, CountsLikeAnOdometerAndNamesFolders) {
  const drapelab::sweep::SweepPlan plan({{"a", {"1", "2"}}, {"b.c", {"x", "[5, 5]", "z"}}});
  ASSERT_EQ(plan.count(), 6u);
  const std::vector<std::vector<std::string>> expected{{"1", "x"}, {"1", "[5, 5]"}, {"1", "z"},
                                                       {"2", "x"}, {"2", "[5, 5]"}, {"2", "z"}};
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(plan.values(k), expected[k]) << k;
  EXPECT_EQ(plan.overrides(4), (std::vector<std::string>{"a=2", "b.c=[5, 5]"}));
  EXPECT_EQ(plan.folder_name(1), "001_a=1_b.c=5_5");
  EXPECT_EQ(drapelab::sweep::sanitise_for_file_name("{ks: 1, kd: 0.5}"), "ks_1_kd_0.5");
  EXPECT_EQ(drapelab::sweep::sanitise_for_file_name("../x/y"),
            ".._x_y");  // no '/' ever reaches a path
  EXPECT_EQ(drapelab::sweep::sanitise_for_file_name("[]"), "_");
  // Eleven hundred combinations: four digits, in order.
  const drapelab::sweep::SweepPlan big({{"k", std::vector<std::string>(1100, "v")}});
  EXPECT_EQ(big.folder_name(7).substr(0, 5), "0007_");
  EXPECT_LE(drapelab::sweep::SweepPlan({{std::string(300, 'k'), {"v"}}}).folder_name(0).size(),
            drapelab::sweep::kMaxFolderName);
}

TEST(SweepValidation, TellsAMisspeltKeyFromABadValue) {
  // Real loader messages for the same scene: only the first three name a key that does not exist.
  struct Case {
    std::string key, value;
    bool key_error;
  };
  const std::vector<Case> cases{
      {"cloth.sprngs.bend.ks", "1", true},    {"cloth.springs.bend.kz", "1", true},
      {"solvers.3.dt", "0.001", true},        {"duration.x", "1", true},
      {"cloth.springs.bend.ks", "-1", false}, {"cloth.springs.bend", "{ks: 1, kq: 2}", false},
      {"cloth.resolution", "[5]", false}};
  for (const auto& c : cases) {
    const auto loaded =
        drapelab::scene::load_scene_text(kSweepSheet, "sheet.yaml", {c.key + "=" + c.value});
    ASSERT_FALSE(loaded.ok()) << c.key;
    bool found = false;
    for (const auto& error : loaded.errors)
      found = found || drapelab::sweep::is_key_path_error(error, c.key, c.value);
    EXPECT_EQ(found, c.key_error) << c.key << "=" << c.value << ": " << loaded.errors.front();
  }
}

}  // namespace
