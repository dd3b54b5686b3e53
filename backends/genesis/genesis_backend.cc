// The Genesis 0.4.x target (`--target genesis`): the shared Python target layer
// (backends/python/python_target.h) with this folder's glue (efc_genesis.py) and
// facts (target.json), both embedded at build time.
#include "backends/python/python_target.h"

namespace efc {

const Backend* genesis_backend() {
  static const PythonTargetBackend backend({"genesis", {}, "Genesis 0.4 Python script over the URDF, with the efc runtime for Python",
                                            embedded_genesis_glue, embedded_genesis_facts});
  return &backend;
}

}  // namespace efc
