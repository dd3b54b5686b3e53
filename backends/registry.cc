#include "backends/backend.h"

namespace efc {

// Each target defines its factory next to its generator, in its own library.
const Backend* mujoco_backend();
const Backend* urdf_backend();
const Backend* bullet_backend();
const Backend* genesis_backend();
const Backend* isaaclab_backend();
const Backend* omnigibson_backend();

const std::vector<const Backend*>& all_backends() {
  static const std::vector<const Backend*> table = {mujoco_backend(),  urdf_backend(),     bullet_backend(),
                                                    genesis_backend(), isaaclab_backend(), omnigibson_backend()};
  return table;
}

const Backend* find_backend(const std::string& name) {
  for (const Backend* b : all_backends()) {
    if (name == b->name()) return b;
    for (const std::string& alias : b->aliases())
      if (name == alias) return b;
  }
  return nullptr;
}

}  // namespace efc
