#include "backends/backend.h"

namespace efc {

bool Backend::emit(const Object& obj, const std::string& dir, Diagnostics& diags) const {
  std::vector<OutputFile> files;
  return generate(obj, diags, &files) && write_output_files(dir, files, diags);
}

}  // namespace efc
