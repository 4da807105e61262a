// The key tables of docs/scene-reference.md, produced from the scene key table
// (scenes/loader/src/scene_keys_*.hpp). In the page a table is the lines between a marker
//   <!-- scene-keys: PARENT [PARENT...] -->
// naming the maps whose keys it lists ("cloth", "solvers[]"; "" is the top level, written as
// `top`), and <!-- /scene-keys -->. Everything outside the markers is prose, kept as it is.
#pragma once

#include <string>
#include <vector>

namespace drapelab::scene {

// The Markdown table of the keys of `parents` (space-separated, as in a marker), in table order.
std::string key_table_markdown(const std::string& parents);

// `markdown` with the table between every pair of markers produced again.
std::string with_key_tables(const std::string& markdown);

// Where the tables of `markdown` disagree with the key table, one line each naming the key and
// the difference: a key missing or extra, a cell (type, default, range, unit, meaning) that
// differs, rows out of order, a marker not closed, a key in no table. Empty when they agree.
std::vector<std::string> key_table_problems(const std::string& markdown);

}  // namespace drapelab::scene
