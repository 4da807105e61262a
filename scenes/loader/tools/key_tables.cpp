// drapelab-key-tables: produces the key tables of docs/scene-reference.md from the scene key table.
//   drapelab-key-tables FILE          writes FILE with every marked table produced again
//   drapelab-key-tables --check FILE  lists where FILE's tables disagree with the key table
// Exit code 0 when written or in agreement, 1 when --check finds differences, 2 on a usage or file
// error. The fast test SceneKeys.ReferenceTablesMatchTheKeyTable runs the check.
#include "drapelab/scene/key_tables.hpp"

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

int main(int argc, char** argv) {
  const bool check = argc == 3 && std::string(argv[1]) == "--check";
  if (argc != 2 && !check) {
    std::cerr << "usage: drapelab-key-tables [--check] docs/scene-reference.md\n";
    return 2;
  }
  const std::string file = argv[argc - 1];
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::cerr << file << ": cannot be read\n";
    return 2;
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (check) {
    const auto problems = drapelab::scene::key_table_problems(text.str());
    for (const std::string& problem : problems) std::cout << file << ": " << problem << "\n";
    return problems.empty() ? 0 : 1;
  }
  const std::string written = drapelab::scene::with_key_tables(text.str());
  in.close();
  std::ofstream out(file, std::ios::binary);
  out << written;
  if (!out) {
    std::cerr << file << ": cannot be written\n";
    return 2;
  }
  return 0;
}
