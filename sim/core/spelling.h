// "did you mean": the name closest to a mistyped one (a command, a JSON key, a preset).
#pragma once

#include <string>
#include <vector>

namespace pelage::sim {

// Edits (insertion, deletion, substitution, swap of two adjacent characters) from `a`
// to `b`: the optimal string alignment distance (Damerau's 1964 operations, each
// substring edited at most once).
size_t edit_distance(const std::string &a, const std::string &b);

// The name in `names` fewest edits away from `typed`, when that is close enough to be a
// typing mistake: at most one edit per three characters of the name, and at least one.
// The first in `names` on a tie; "" when none is close.
std::string closest_name(const std::string &typed, const std::vector<std::string> &names);

}  // namespace pelage::sim
