// A small harness for end-to-end tests of the drapelab command line: run the built binary with
// arguments (capturing stdout and stderr together, and the exit code), and give each test a fresh
// temporary folder that is removed afterwards.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace drapelab::testing {

struct CommandResult {
  int exit_code = -1;   // the process's exit status (WEXITSTATUS), -1 when it did not exit normally
  std::string output;   // stdout and stderr, interleaved as written
};

// Quotes one argument for /bin/sh (single quotes, embedded quotes escaped).
std::string shell_quote(const std::string& argument);

// Runs the drapelab binary (DRAPELAB_EXE) with `arguments`, from the current working directory.
CommandResult run_drapelab(const std::vector<std::string>& arguments);

// Starts the drapelab binary with `arguments` as a child process whose output is thrown away, waits
// (up to `timeout`) until `ready()` holds, sends it SIGINT (Ctrl-C) and waits for it to end. Returns
// its exit status, or -1 when it did not exit normally. For the tests of what an interrupt leaves.
int interrupt_drapelab_when(const std::vector<std::string>& arguments, const std::function<bool()>& ready,
                            std::chrono::seconds timeout = std::chrono::seconds(60));

// Whole-file helpers.
std::string read_text(const std::filesystem::path& path);
void write_text(const std::filesystem::path& path, const std::string& text);

// Splits text into lines (without the '\n'); a final newline does not add an empty line.
std::vector<std::string> split_lines(const std::string& text);
// Splits one CSV line on commas (drapelab's CSV cells never hold commas or quotes).
std::vector<std::string> split_csv(const std::string& line);

// A fresh, uniquely named folder under the system temporary folder, created in SetUp and removed
// (with everything in it) in TearDown.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace drapelab::testing
