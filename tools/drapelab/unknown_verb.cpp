#include "unknown_verb.hpp"

#include <algorithm>

#include "drapelab/scene/edit_distance.hpp"

namespace drapelab::cli {
using scene::edit_distance;

std::optional<std::string> nearest_verb(const std::string& word,
                                        const std::vector<std::string>& verbs) {
  // The scene loader's rule for misspelt keys: a third of the word's letters, at least 2.
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  std::optional<std::string> best;
  for (const auto& verb : verbs) {
    const std::size_t distance = edit_distance(word, verb);
    if (distance < best_distance) {
      best_distance = distance;
      best = verb;
    }
  }
  if (best || word.size() < 2) return best;
  // A verb cut short ("vali", "rend") is far by distance but plain to read, when it is the only
  // verb that begins so ("st" could be stability or study).
  std::vector<std::string> beginning;
  for (const auto& verb : verbs)
    if (verb.rfind(word, 0) == 0) beginning.push_back(verb);
  if (beginning.size() == 1) return beginning.front();
  return std::nullopt;
}

std::optional<std::string> unknown_verb_message(int argc, const char* const* argv,
                                                const CLI::App& app) {
  // drapelab's own options are flags (--help, --version): the first other word is the verb.
  std::string word;
  for (int k = 1; k < argc && word.empty(); ++k)
    if (argv[k][0] != '-') word = argv[k];
  if (word.empty()) return std::nullopt;
  std::vector<std::string> verbs;
  for (const CLI::App* verb : app.get_subcommands([](const CLI::App*) { return true; }))
    verbs.push_back(verb->get_name());
  if (std::find(verbs.begin(), verbs.end(), word) != verbs.end()) return std::nullopt;
  if (const auto nearest = nearest_verb(word, verbs))
    return "unknown command '" + word + "'; did you mean '" + *nearest + "'?";
  std::string list;
  for (const auto& verb : verbs) list += (list.empty() ? "" : ", ") + verb;
  return "unknown command '" + word + "'; the commands are " + list +
         " ('drapelab --help' says what each does)";
}

}  // namespace drapelab::cli
