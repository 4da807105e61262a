// The verbs of the drapelab command line, each a function from parsed arguments to an exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <atomic>
#include <string>
#include <vector>

namespace drapelab::cli {

inline constexpr int kExitBadInput = 2;

struct RunArguments {
  std::string scene;
  std::string out;
  std::vector<std::string> overrides;  // --set key.path=value
  std::string meshes;                  // --meshes obj|pc2|both (shorthand for --set output.meshes=...)
  bool force = false;
  bool quiet = false;
};
void add_run_options(CLI::App& verb, RunArguments& arguments);
int run_verb(const RunArguments& arguments, const std::string& command_line, const std::atomic<bool>& interrupt);

struct ValidateArguments {
  std::string scene;
  std::vector<std::string> overrides;
  bool print_resolved = false;
};
void add_validate_options(CLI::App& verb, ValidateArguments& arguments);
int validate_verb(const ValidateArguments& arguments);

struct CheckArguments {
  std::string scene;
  std::string golden;
  std::vector<std::string> overrides;  // with --update only
  std::string out;
  bool update = false;
};
void add_check_options(CLI::App& verb, CheckArguments& arguments);
int check_verb(const CheckArguments& arguments, const std::atomic<bool>& interrupt);

}  // namespace drapelab::cli
