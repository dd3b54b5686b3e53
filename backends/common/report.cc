#include "backends/common/report.h"

namespace efc {

SourceLoc spec_location(const Object& obj, const std::string& pointer) {
  SourceLoc loc;
  loc.pointer = pointer;
  std::string p = pointer;
  while (true) {
    const auto it = obj.positions.find(p);
    if (it != obj.positions.end()) {
      loc.line = it->second.first;
      loc.col = it->second.second;
      return loc;
    }
    if (p.empty()) return loc;
    p = p.substr(0, p.rfind('/'));
  }
}

void warn_target(Diagnostics& diags, const Object& obj, const SourceLoc& loc,
                 const std::string& message) {
  diags.warning("W0900", obj.file, loc.line, loc.col, loc.pointer, message);
}

}  // namespace efc
