// The OmniGibson 3.7 target (`--target omnigibson`): the shared Python target layer
// (backends/python/python_target.h) with this folder's glue (efc_omnigibson.py) and
// facts (target.json), both embedded at build time.
#include "backends/python/python_target.h"

namespace efc {

const Backend* omnigibson_backend() {
  static const PythonTargetBackend backend({"omnigibson", {"behavior"}, "OmniGibson 3.7 (BEHAVIOR-1K) Python script over the URDF, with the efc runtime for Python",
                                            embedded_omnigibson_glue, embedded_omnigibson_facts});
  return &backend;
}

}  // namespace efc
