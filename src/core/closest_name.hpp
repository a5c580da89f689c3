// Suggestions for a misspelt name (an unknown key of a scene or style file): the known name
// nearest to it by edit distance, counting insertions, deletions, substitutions and swaps of
// two neighbouring letters as one edit each (optimal string alignment), when it is near enough to
// be what was meant: at most 2 edits and fewer than half the name's letters.
#pragma once
#include <string>
#include <vector>

namespace penink {

// Edits between a and b (optimal string alignment distance).
std::size_t edit_distance(const std::string& a, const std::string& b);

// The nearest of `known` to `name` within the bound above (the first of equals in `known`'s
// order), "" when none is.
std::string closest_name(const std::string& name, const std::vector<std::string>& known);

// "; did you mean NAME?" for closest_name's answer, "" when it has none.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& known);

}  // namespace penink
