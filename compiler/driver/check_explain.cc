// efc check and efc explain.
#include <iostream>

#include "compiler/core/ir_json.h"
#include "compiler/core/load.h"
#include "compiler/driver/commands.h"

namespace efc {

int cmd_check(const std::vector<std::string>& specs, bool dump_ir, const CommonOptions& common) {
  int rc = 0;
  nlohmann::json dumps = nlohmann::json::array();
  for (const std::string& spec : specs) {
    Diagnostics diags;
    LoadOptions opts;
    opts.allow_absolute_paths = common.allow_absolute_paths;
    bool io_error = false;
    std::optional<Object> obj = load_spec(spec, opts, diags, &io_error);
    diags.print(std::cerr, common.json_diagnostics);
    if (!obj) {
      rc = std::max(rc, io_error ? 2 : 1);
      continue;
    }
    if (dump_ir) dumps.push_back(ir_to_json(*obj));
  }
  if (dump_ir && rc == 0) {
    const nlohmann::json& out = dumps.size() == 1 ? dumps[0] : dumps;
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  }
  return rc;
}

int cmd_explain(const std::string& code, bool list) {
  if (list || code.empty()) {
    for (const CodeInfo& c : all_codes()) std::cout << c.code << "  " << c.title << "\n";
    return 0;
  }
  const CodeInfo* info = find_code(code);
  if (!info) {
    std::cerr << "efc explain: unknown code '" << code << "' (efc explain --list shows them all)\n";
    return 2;
  }
  std::cout << info->code << ": " << info->title << "\n\n" << info->explanation << "\n";
  return 0;
}

}  // namespace efc
