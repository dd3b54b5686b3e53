// efc explain CODE | --list: what a diagnostic means and how to fix it.
#include <iostream>

#include "cli/commands.h"

namespace efc {

int cmd_explain(Report& report, const std::string& code, bool list) {
  if (list || code.empty()) {
    for (const CodeInfo& c : all_codes()) std::cout << c.code << "  " << c.title << "\n";
    return kExitOk;
  }
  const CodeInfo* info = find_code(code);
  if (!info)
    return report.fail("E0910", "unknown code '" + code + "'", kExitUsage,
                       "efc explain --list shows them all");
  std::cout << info->code << ": " << info->title << "\n\n" << info->explanation << "\n";
  return kExitOk;
}

}  // namespace efc
