// "Did you mean ...?" for misspelt keys, enum values and part names.
#pragma once

#include <string>
#include <vector>

namespace efc::frontend {

// The candidate closest to `word` by edit distance when it is close enough to
// be a plausible typo (distance <= 1 for short words, else max(2, size/3)); "" otherwise.
std::string closest(const std::string& word, const std::vector<std::string>& candidates);

// "did you mean 'x'?" or "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace efc::frontend
