#include "harness/mujoco_errors.h"

#include <mujoco/mujoco.h>

#include <mutex>

namespace efc {
namespace {

std::mutex g_mutex;
std::vector<std::string> g_warnings;

// Throwing through MuJoCo's C frames is safe with GCC on x86-64 (unwind
// tables are on by default); the alternative, returning, lets MuJoCo exit().
[[noreturn]] void on_error(const char* msg) { throw MujocoError(std::string("MuJoCo: ") + msg); }

void on_warning(const char* msg) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_warnings.emplace_back(msg);
}

}  // namespace

void install_mujoco_handlers() {
  mju_user_error = on_error;
  mju_user_warning = on_warning;
}

std::vector<std::string> take_mujoco_warnings() {
  std::lock_guard<std::mutex> lock(g_mutex);
  std::vector<std::string> out;
  out.swap(g_warnings);
  return out;
}

}  // namespace efc
