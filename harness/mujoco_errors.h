// MuJoCo's default error handler prints and waits for Enter; its warnings go
// to stdout. Every efc program installs these handlers instead: errors become
// C++ exceptions (caught by the caller), warnings are collected.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace efc {

struct MujocoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Idempotent. After this, mju_error throws MujocoError and mju_warning records.
void install_mujoco_handlers();
// Warnings recorded since the last call (and clears them).
std::vector<std::string> take_mujoco_warnings();

}  // namespace efc
