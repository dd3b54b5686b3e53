// libFuzzer target: bytes -> efc::read_json_text -> (an object) check_structure.
// The JSON front-end must never crash, hang, leak or hit undefined behaviour,
// whatever the bytes; and (fuzz_common.h) it never rejects a document without
// an error, every diagnostic has a catalogued code and a position inside the
// text. A document the reader accepts must also survive both spellings
// (compiler/frontend/dsl.h: parse(print(doc)) == doc for every document the
// JSON reader accepts): efc::dsl::print then dsl::parse, and dsl::print_json
// then the JSON parser, give the same value back.
// Run with scripts/fuzz (tests/fuzz/README.md).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <string_view>

#include "compiler/frontend/check.h"
#include "compiler/frontend/dsl.h"
#include "compiler/frontend/json_reader.h"
#include "compiler/frontend/positioned_json.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

std::string diagnostics_text(const efc::Diagnostics& diags) {
  std::string out;
  for (const efc::Diagnostic& d : diags.items()) out += efc::format_text(d);
  return out;
}

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

  // The accepted document through the DSL and back, and through print_json.
  efc::Diagnostics dom_diags;
  auto dom = efc::frontend::parse_positioned(text, "fuzz.json", opts.max_depth, dom_diags);
  if (!dom) efc_fuzz::fail("parse_positioned rejects a document read_json_text accepted", text);
  const std::string efc_text = efc::dsl::print(dom->value);
  efc::Diagnostics dsl_diags;
  auto back = efc::dsl::parse(efc_text, "printed.efc", opts.max_depth, dsl_diags);
  if (!back || back->value != dom->value)
    efc_fuzz::fail("dsl::parse(dsl::print(doc)) != doc for a document the reader accepts:\n"
                   "--- document\n" + dom->value.dump(1) + "\n--- printed\n" + efc_text +
                       "\n--- reparsed\n" + (back ? back->value.dump(1) : "(nothing)") +
                       "\n--- errors\n" + diagnostics_text(dsl_diags),
                   text);
  const std::string json_text = efc::dsl::print_json(dom->value);
  efc::Diagnostics json_diags;
  auto again = efc::frontend::parse_positioned(json_text, "printed.json", opts.max_depth, json_diags);
  if (!again || again->value != dom->value)
    efc_fuzz::fail("print_json(doc) does not read back to doc:\n--- document\n" +
                       dom->value.dump(1) + "\n--- print_json\n" + json_text + "\n--- errors\n" +
                       diagnostics_text(json_diags),
                   text);
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
