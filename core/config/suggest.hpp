#pragma once
// "Did you mean" suggestions for misspelt keys and choices.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace suite {

// Edit distance (insertions, deletions, substitutions, adjacent transpositions).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word`, if it is close enough to be a plausible typo:
// distance <= 1 for words under 4 letters, else <= max(2, |word| / 3); or a case-insensitive match.
std::optional<std::string> closest_match(std::string_view word, const std::vector<std::string>& candidates);

// "a, b, c" for messages.
std::string join(const std::vector<std::string>& items, std::string_view sep = ", ");

}  // namespace suite
