// efc check SPEC... [--dump-ir]: read and type-check; write nothing (but the
// IR dump on stdout).
#include <iostream>

#include "cli/commands.h"
#include "compiler/core/ir_json.h"

namespace efc {

int cmd_check(Report& report, const std::vector<std::string>& specs, bool dump_ir) {
  int rc = kExitOk;
  const std::vector<Object> objects = load_all(report, specs, &rc);
  if (dump_ir && rc == kExitOk) {
    nlohmann::json dumps = nlohmann::json::array();
    for (const Object& obj : objects) dumps.push_back(ir_to_json(obj));
    const nlohmann::json& out = dumps.size() == 1 ? dumps[0] : dumps;
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  }
  return rc;
}

}  // namespace efc
