// Limits that hold before memory is taken, paths that name a file as written, and error output
// that stays short (docs/scene-reference.md, "Rules that apply across keys"): the cases of the
// reliability review (issue 41) at the loader, each with its line, key and limit.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base_scene.hpp"
#include "fixtures/scene_text.hpp"
#include "run_memory.hpp"
#include "text_checks.hpp"
#include "tree_limits.hpp"
#include "yaml_reader.hpp"

namespace {

using namespace drapelab::fixtures;      // fixtures/scene_text.hpp
using namespace drapelab::loader_tests;  // base_scene.hpp
namespace scene = drapelab::scene;

// kMinimal with `lines` appended, each "\n"-terminated.
std::string minimal_with(const std::string& lines) { return kMinimal + lines; }

// `count` lines made by `line(k)`.
template <typename Line>
std::string repeated(int count, Line line) {
  std::string text;
  for (int k = 0; k < count; ++k) text += line(k);
  return text;
}

// ---------------------------------------------------------------------------------------------
// Error output: 20 errors and a count; long values cut with their length

TEST(InputLimits, AHundredThousandUnknownKeysGiveTwentyErrorsAndACount) {
  const auto result = load(
      minimal_with(repeated(100'000, [](int k) { return "junk" + std::to_string(k) + ": 1\n"; })));
  ASSERT_EQ(result.errors.size(), scene::kMaxListedErrors + 1);
  EXPECT_TRUE(HasError(result, at(7), {"junk0 is not a known key"}));
  EXPECT_EQ(result.errors.back(),
            std::string(kName) +
                ": 99980 more errors are not listed (only the first 20 are); correct these and "
                "check again");
}

TEST(InputLimits, AHundredThousandDigitNumberIsShownCutWithItsLength) {
  const std::string digits(100'000, '1');
  const auto result = load(with_line(kBase, 13, "  mass: " + digits));
  EXPECT_TRUE(HasError(result, at(13),
                       {"cloth.mass must be a number (>= 1e-09 and <= 1e+06), got '" +
                            std::string(40, '1') + "...' (100000 characters)",
                        "beyond what a double holds"}));
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_LT(result.errors.front().size(), 200u);
  // The same value in a --set: the override is cut where it names the location too.
  const auto set = load(kBase, {"cloth.mass=" + digits});
  ASSERT_EQ(set.errors.size(), 1u);
  EXPECT_LT(set.errors.front().size(), 500u);
  EXPECT_NE(set.errors.front().find("--set cloth.mass=" + std::string(159, '1') +
                                    "... (100017 characters): cloth.mass must be a number"),
            std::string::npos)
      << set.errors.front();
}

TEST(InputLimits, ALongUnknownKeyIsShownCut) {
  const std::string key(1000, 'k');  // yaml-cpp's longest key without "? "
  const auto result = load(minimal_with(key + ": 1\n"));
  EXPECT_TRUE(
      HasError(result, at(7), {std::string(40, 'k') + "... (1000 characters) is not a known key"}));
}

TEST(InputLimits, ShownValuesAreCutOnACharacterBoundary) {
  EXPECT_EQ(scene::shown_value("short"), "short");
  EXPECT_EQ(scene::quoted_value("short"), "'short'");
  // 39 ASCII bytes and then a 2-byte character across the 40-byte cut: the character is kept out
  // whole.
  const std::string text = std::string(39, 'a') + "\xc3\xa9" + std::string(100, 'b');
  EXPECT_EQ(scene::shown_value(text), std::string(39, 'a') + "... (140 characters)");
  EXPECT_EQ(scene::listed_names({"a", "b", "c", "d", "e", "f", "g", "h", "i", "j"}),
            "a, b, c, d, e, f, g, h and 2 more");
}

// ---------------------------------------------------------------------------------------------
// Sizes from the scene's numbers, before anything is allocated

TEST(InputLimits, ATwoThousandSquareSheetIsRefusedAtItsResolution) {
  const auto result = load(with_line(kBase, 10, "  resolution: [2000, 2000]"));
  EXPECT_TRUE(
      HasError(result, at(10), {"cloth.resolution gives 4000000 particles; at most 1000000"}));
  EXPECT_LOADS(load(with_line(kMinimal, 4, "  resolution: [1000, 2]")));
}

TEST(InputLimits, ListsLongerThanTheirLimitAreRefusedBeforeTheTreeIsBuilt) {
  struct Case {
    std::string text;
    int line;
    std::string message;
  };
  const std::vector<Case> cases = {
      {with_line(kBase, 21,
                 "  pins:\n" + repeated(1'000'000, [](int) { return "    - {index: 2}\n"; })),
       21, "cloth.pins has more than 10000 pin selectors; at most 10000 are allowed"},
      {minimal_with("colliders:\n" +
                    repeated(100'000,
                             [](int k) {
                               return "  - {name: c" + std::to_string(k) +
                                      ", type: sphere, center: [0, -5, 0], radius: 0.1}\n";
                             })),
       7, "colliders has more than 1000 colliders; at most 1000 are allowed"},
      {minimal_with("colliders:\n  - name: arm\n    type: sphere\n    radius: 0.1\n    motion:\n"
                    "      keyframes:\n" +
                    repeated(30'001,
                             [](int k) {
                               return "        - {t: " + std::to_string(k) +
                                      ", center: [0, -5, 0]}\n";
                             })),
       12, "colliders.0.motion.keyframes has more than 30000 keyframes; at most 30000"},
      {minimal_with(
           "constraints:\n" +
           repeated(
               20'001,
               [](int) { return "  - {type: distance, a: {index: 0}, b: {point: [0, 2, 0]}}\n"; })),
       7, "constraints has more than 20000 constraints; at most 20000"},
      {minimal_with(
           "interactions:\n" +
           repeated(1'001,
                    [](int) {
                      return "  - {type: drag, particle: {index: 0}, stiffness: 1, keyframes: "
                             "[{t: 0, target: [0, 1, 0]}]}\n";
                    })),
       7, "interactions has more than 1000 interactions; at most 1000"},
      {minimal_with("junk: [" + repeated(600'000, [](int) { return "0, "; }) + "0]\n"), 7,
       "is past the 500000 values, lists and maps a scene may hold"},
  };
  for (const Case& c : cases) {
    const auto result = load(c.text);
    EXPECT_TRUE(HasError(result, at(c.line), {c.message})) << c.message;
    EXPECT_EQ(result.errors.size(), 1u);
  }
}

TEST(InputLimits, AnOverridesListsAreCountedToo) {
  const std::string set =
      "cloth.pins=[" + repeated(10'001, [](int) { return "corners, "; }) + "corners]";
  const auto result = load(kBase, {set});
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_NE(result.errors.front().find(": cloth.pins has more than 10000 pin selectors"),
            std::string::npos)
      << result.errors.front();
  EXPECT_LOADS(load(kBase, {"cloth.pins=[corners, corners]"}));
}

TEST(InputLimits, TreeLimitsMatchListsByTheirKeyPath) {
  EXPECT_FALSE(scene::tree_size_problem("a: [1, 2, 3]\ncloth: {pins: [corners]}\n", ""));
  const auto nested =
      scene::tree_size_problem("[" + repeated(30'001, [](int) { return "{t: 0}, "; }) + "{t: 1}]",
                               "interactions.3.keyframes");
  ASSERT_TRUE(nested);
  EXPECT_EQ(nested->path, "interactions.3.keyframes");
  EXPECT_EQ(nested->line, 0);
  // Not valid YAML: nothing here, YAML::Load reports it.
  EXPECT_FALSE(scene::tree_size_problem("a: [1, 2", ""));
}

TEST(InputLimits, ARunTooLargeForTheProcessIsRefusedAtTheClothsSize) {
  const YAML::Node solvers = YAML::Load(
      "[{type: spring_damper}, {name: classic, type: bullet_softbody}, "
      "{type: bullet_deformable}]");
  const auto parts = scene::run_memory_parts(1e6, solvers, false);
  ASSERT_EQ(parts.size(), 4u);
  EXPECT_EQ(parts[2].what, "solver classic (bullet_softbody)");
  const auto problem = scene::run_memory_problem(1e6, parts, {3e9, "the address space limit"});
  ASSERT_TRUE(problem);
  EXPECT_EQ(*problem,
            "gives 1000000 particles, and a run of them needs about 8100 MB of memory (1600 MB "
            "for the cloth, its metrics and outputs, 1400 MB for solver spring_damper, 2300 MB "
            "for solver classic (bullet_softbody), 2800 MB for solver bullet_deformable), more "
            "than the 3000 MB this process may use (the address space limit); use fewer "
            "particles or fewer solvers");
  EXPECT_FALSE(scene::run_memory_problem(1e6, parts, {9e9, "physical memory"}));
  // Our solver's self-contact takes memory of its own.
  EXPECT_GT(scene::run_memory_parts(1e6, solvers, true)[1].bytes, parts[1].bytes);
  // The bound is at most the machine's memory, and at least what this test process uses.
  const auto bound = scene::usable_memory();
  ASSERT_TRUE(bound);
  EXPECT_GT(bound->bytes, 1e8);
}

// ---------------------------------------------------------------------------------------------
// Paths: control characters refused with the key

TEST(InputLimits, APathWithANulByteOrAControlCharacterIsRefusedWithItsKey) {
  const std::string mesh = "name: m\nduration: 0.1\ncloth:\n  shape: mesh\n  path: ";
  const std::string rest = "\n  mass: 0.1\nsolvers: [{type: spring_damper}]\n";
  EXPECT_TRUE(HasError(load(mesh + "\"good.obj\\0x\"" + rest), at(5),
                       {"cloth.path holds a NUL byte (\\0) at character 9, which would end the "
                        "file name there"}));
  EXPECT_TRUE(HasError(load(mesh + "\"good\\t.obj\"" + rest), at(5),
                       {"cloth.path holds the control character 0x09 at character 5"}));
  EXPECT_TRUE(HasError(load(mesh + "x" + rest, {"cloth.path=\"a\\x1b.obj\""}),
                       at_set("cloth.path=\"a\\x1b.obj\""),
                       {"cloth.path holds the control character 0x1b at character 2"}));
}

}  // namespace
