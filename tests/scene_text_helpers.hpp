// Helpers for scene loader tests: edit a scene's text by line number, and assert that loading it
// failed with an error at a given location that contains given fragments.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::testing {

std::vector<std::string> lines_of(const std::string& text);
std::string join_lines(const std::vector<std::string>& lines);
// Replaces 1-based line `number` of `text` with `replacement` (which may hold several lines).
std::string with_line(const std::string& text, int number, const std::string& replacement);
// Removes lines first..last (1-based, inclusive).
std::string without_lines(const std::string& text, int first, int last);
// Inserts `inserted` (one or more lines, no final newline needed) after 1-based line `number`.
std::string insert_after(const std::string& text, int number, const std::string& inserted);

// Every error of a load, one per line, for failure messages.
std::string all_errors(const scene::LoadResult& result);

// The load failed and one single error message starts with `location` (e.g. "drape_test.yaml:18:"
// or "drape_test.yaml: --set a.b=1:") and contains every fragment (key path, expected wording...).
::testing::AssertionResult HasError(const scene::LoadResult& result, const std::string& location,
                                    const std::vector<std::string>& fragments);

// Location prefixes: a line of the scene, and a --set override.
std::string at_line(const std::string& file, int line);
std::string at_override(const std::string& file, const std::string& override_text);

}  // namespace drapelab::testing

#define EXPECT_LOADS(result) EXPECT_TRUE((result).ok()) << "errors:" << ::drapelab::testing::all_errors(result)
#define ASSERT_LOADS(result) ASSERT_TRUE((result).ok()) << "errors:" << ::drapelab::testing::all_errors(result)
