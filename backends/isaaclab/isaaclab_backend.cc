// The Isaac Lab 2.3 target (`--target isaaclab`): the shared Python target layer
// (backends/python/python_target.h) with this folder's glue (efc_isaaclab.py) and
// facts (target.json), both embedded at build time.
#include "backends/python/python_target.h"

namespace efc {

const Backend* isaaclab_backend() {
  static const PythonTargetBackend backend({"isaaclab", {"isaac"}, "Isaac Lab 2.3 (Isaac Sim 5.1) Python script over the URDF, with the efc runtime for Python",
                                            embedded_isaaclab_glue, embedded_isaaclab_facts});
  return &backend;
}

}  // namespace efc
