#include "pipeline/egofun3d/names.h"

#include <cctype>

namespace efc::egofun3d {

std::string sanitize_name(const std::string& label, const std::string& fallback) {
  std::string out;
  for (unsigned char c : label) {
    const bool ok = std::isalnum(c) || c == '_';
    if (ok && c < 128)
      out += static_cast<char>(c);
    else if (!out.empty() && out.back() != '_')
      out += '_';
  }
  while (!out.empty() && out.back() == '_' && out.size() > 1) out.pop_back();
  if (out.empty() || out == "_") out = fallback;
  if (std::isdigit(static_cast<unsigned char>(out[0]))) out = "p_" + out;
  if (out.size() > 64) out.resize(64);
  return out;
}

std::string unique_name(const std::string& name, std::set<std::string>* taken) {
  std::string candidate = name;
  for (int k = 2; taken->count(candidate); ++k) {
    const std::string suffix = "_" + std::to_string(k);
    candidate = name.substr(0, 64 - suffix.size()) + suffix;
  }
  taken->insert(candidate);
  return candidate;
}

std::string sanitize_folder(const std::string& video_name) {
  std::string out;
  for (unsigned char c : video_name) {
    const bool ok = (std::isalnum(c) && c < 128) || c == '.' || c == '_' || c == '-';
    out += ok ? static_cast<char>(c) : '_';
  }
  while (!out.empty() && out[0] == '.') out[0] = '_';
  if (out.size() > 128) out.resize(128);
  if (out.empty()) out = "video";
  return out;
}

}  // namespace efc::egofun3d
