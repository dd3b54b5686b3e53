// Writing a backend's text outputs: one helper for every target.
#pragma once

#include <string>

namespace efc {

// Writes `text` to `path` (binary, so line endings are exactly as generated).
// False with the reason in *error (the system's message) on failure.
bool write_text_file(const std::string& path, const std::string& text, std::string* error);

}  // namespace efc
