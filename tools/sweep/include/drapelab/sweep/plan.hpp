// The plan of a sweep: the varied keys and their values (parsed from --vary), the combinations in
// their fixed order, and the name of each combination's run folder.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::sweep {

// One --vary option: a scene key path (as --set takes it) and the values it takes, in the order
// given. Each value is YAML text, exactly as it would follow "key=" in --set.
struct VariedKey {
  std::string key;
  std::vector<std::string> values;
};

// Splits "v1,v2,..." on the commas that are outside brackets, braces and quotes, so that a YAML
// flow list or map is one value: "[5,5],[7,7]" -> "[5,5]", "[7,7]". Spaces around a value are
// dropped. Returns nothing with `error` set when a value is empty or a bracket or quote is left
// open.
std::optional<std::vector<std::string>> split_values(const std::string& text, std::string* error);

// Parses "key.path=v1,v2,...". Returns nothing with `error` set when there is no '=', the key is
// empty or has an empty part, or the values do not split (split_values).
std::optional<VariedKey> parse_vary(const std::string& text, std::string* error);

// The combinations of a sweep, numbered 0..count()-1 in odometer order: the last --vary key changes
// fastest and the first slowest, as nested loops written in the order of the --vary options. With
// --vary a=1,2 --vary b=x,y,z: 0 (a=1, b=x), 1 (1, y), 2 (1, z), 3 (2, x), 4 (2, y), 5 (2, z).
class SweepPlan {
 public:
  explicit SweepPlan(std::vector<VariedKey> keys);

  const std::vector<VariedKey>& keys() const { return keys_; }
  std::size_t count() const { return count_; }  // the product of the value counts

  // The value index of each key in combination `index`.
  std::vector<std::size_t> value_indices(std::size_t index) const;
  // The value of each key in combination `index`.
  std::vector<std::string> values(std::size_t index) const;
  // "key=value" overrides of combination `index`, in key order (appended after the --set ones).
  std::vector<std::string> overrides(std::size_t index) const;
  // The index zero-padded to the width of the largest index, at least three digits: "007".
  std::string index_label(std::size_t index) const;
  // The run folder's name: "NNN_key=value_key=value", NNN the zero-padded index (at least three
  // digits), key paths and values sanitised for a file name (sanitise_for_file_name) and the whole
  // name cut to kMaxFolderName bytes (the index keeps names unique).
  std::string folder_name(std::size_t index) const;

 private:
  std::vector<VariedKey> keys_;
  std::size_t count_ = 1;
};

// Most bytes in a run folder's name: well under the usual 255-byte limit of a file name.
inline constexpr std::size_t kMaxFolderName = 160;

// Keeps letters, digits and . + - =; any other run of characters becomes one '_', and '_' at the
// ends is dropped: "[5, 5]" -> "5_5", "{ks: 1}" -> "ks_1". An empty result becomes "_".
std::string sanitise_for_file_name(const std::string& text);

}  // namespace drapelab::sweep
