// libFuzzer target: bytes -> efc::read_json_text -> (an object) check_structure.
// The JSON front-end must never crash, hang, leak or hit undefined behaviour,
// whatever the bytes; and (fuzz_common.h) it never rejects a document without
// an error, every diagnostic has a catalogued code and a position inside the
// text. Run with scripts/fuzz (tests/fuzz/README.md).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <string_view>

#include "compiler/frontend/check.h"
#include "compiler/frontend/json_reader.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

void run(std::string_view text) {
  efc::Diagnostics diags;
  efc::ReadOptions opts;  // max_depth 256, absolute paths refused
  std::optional<efc::Object> obj =
      efc::read_json_text(text, "fuzz.json", efc_fuzz::base_dir(), opts, diags);
  efc_fuzz::check_diagnostics(diags, text, !obj, "read_json_text");
  if (!obj) return;
  if (diags.has_errors()) efc_fuzz::fail("read_json_text returned an object with errors", text);
  efc::Diagnostics checks;
  efc::check_structure(*obj, checks);
  efc_fuzz::check_diagnostics(checks, text, false, "check_structure");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    run(text);
  } catch (const std::exception& e) {
    efc_fuzz::fail(std::string("exception escaped: ") + e.what(), text);
  }
  return 0;
}
