// Names the importer makes from the dataset's free-text labels ("Faucet
// Handle", "stove knob #2"): part and function names must match the spec's
// ^[A-Za-z_][A-Za-z0-9_]{0,63}$ (they reach generated XML, C++ and Python),
// and sequence folders must be one safe path component.
#pragma once

#include <set>
#include <string>

namespace efc::egofun3d {

// Every character outside [A-Za-z0-9_] becomes '_' (runs collapse to one,
// ends are trimmed); a leading digit gets "p_" in front; an empty result is
// `fallback`; at most 64 characters. "Faucet Handle" -> "Faucet_Handle".
std::string sanitize_name(const std::string& label, const std::string& fallback = "part");
// `name`, or name_2, name_3, ... (still at most 64 characters) if taken; adds
// the result to *taken.
std::string unique_name(const std::string& name, std::set<std::string>* taken);
// A sequence folder name: [A-Za-z0-9._-] kept, everything else '_', no
// leading '.', at most 128 characters; "video" when nothing is left.
std::string sanitize_folder(const std::string& video_name);

}  // namespace efc::egofun3d
