#pragma once
// "did you mean 'emission'?": the known name nearest a misspelt one, so that
// a typo in a scene file or a flag is an error that shows the fix, not a
// field silently left at its default.
#include <string>
#include <string_view>
#include <vector>

namespace illum {

// Levenshtein distance: insertions, deletions and substitutions.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The nearest of `known` when it is within max(2, |name|/3) edits, else "".
std::string nearest_name(std::string_view name, const std::vector<std::string_view>& known);

// "unknown field 'emision' (did you mean 'emission'?); the known fields here are 'reflectance', 'emission'"
std::string unknown_name_message(const std::string& kind, std::string_view name,
                                 const std::vector<std::string_view>& known);

}  // namespace illum
