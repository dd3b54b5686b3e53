// libFuzzer target for the DSL front-end (compiler/frontend/dsl.h):
//   bytes -> efc::dsl::parse; it must never crash, hang, leak or hit undefined
//   behaviour, and (fuzz_common.h) never reject text without an error, every
//   diagnostic with a catalogued code and a position inside the text.
// When parse returns a document, three oracles:
//   round trip   print(doc) must parse again, to the same value (dsl.h: parse(print(doc)) == doc)
//   comments     print(doc, comments) too, and keeps every comment (`efc fmt` loses none)
//   JSON twin    print_json(doc) must be JSON the JSON reader's parser reads to the same value
//   checks       the document goes through build_object and check_structure as
//                the JSON reader's would (positions into the .efc text), and
//                their diagnostics pass the same checks
// A failed oracle prints what differs and traps (libFuzzer saves the input).
// Run with scripts/fuzz (tests/fuzz/README.md).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <string_view>

#include "compiler/frontend/check.h"
#include "compiler/frontend/dsl.h"
#include "compiler/frontend/positioned_json.h"
#include "compiler/frontend/spec_builder.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

constexpr size_t kMaxDepth = 256;  // ReadOptions' default

std::string diagnostics_text(const efc::Diagnostics& diags) {
  std::string out;
  for (const efc::Diagnostic& d : diags.items()) out += efc::format_text(d);
  return out;
}

void run(std::string_view text) {
  efc::Diagnostics diags;
  efc::dsl::CommentMap comments;
  std::optional<efc::frontend::PositionedJson> doc =
      efc::dsl::parse_with_comments(text, "fuzz.efc", kMaxDepth, diags, &comments);
  efc_fuzz::check_diagnostics(diags, text, !doc, "dsl::parse");
  if (!doc) return;
  if (diags.has_errors()) efc_fuzz::fail("dsl::parse returned a document with errors", text);

  // Round trip through the canonical .efc text.
  const std::string printed = efc::dsl::print(doc->value);
  efc::Diagnostics again_diags;
  auto again = efc::dsl::parse(printed, "printed.efc", kMaxDepth, again_diags);
  if (!again)
    efc_fuzz::fail("print(doc) does not parse again:\n--- document\n" + doc->value.dump(1) +
                       "\n--- printed\n" + printed + "\n--- errors\n" +
                       diagnostics_text(again_diags),
                   text);
  if (again->value != doc->value)
    efc_fuzz::fail("parse(print(doc)) != doc:\n--- document\n" + doc->value.dump(1) +
                       "\n--- printed\n" + printed + "\n--- reparsed\n" + again->value.dump(1) +
                       "\n--- patch document -> reparsed\n" +
                       nlohmann::json::diff(doc->value, again->value).dump(1),
                   text);

  // With the comments put back (efc fmt): the same value, every comment kept.
  const std::string formatted = efc::dsl::print(doc->value, &comments);
  efc::Diagnostics fmt_diags;
  efc::dsl::CommentMap fmt_comments;
  auto reformatted = efc::dsl::parse_with_comments(formatted, "formatted.efc", kMaxDepth,
                                                   fmt_diags, &fmt_comments);
  if (!reformatted || reformatted->value != doc->value)
    efc_fuzz::fail("print(doc, comments) does not parse back to doc:\n--- document\n" +
                       doc->value.dump(1) + "\n--- printed with comments\n" + formatted +
                       "\n--- errors\n" + diagnostics_text(fmt_diags),
                   text);
  if (fmt_comments.size() != comments.size())
    efc_fuzz::fail("print(doc, comments) keeps " + std::to_string(fmt_comments.size()) + " of " +
                       std::to_string(comments.size()) + " comments:\n--- printed\n" + formatted,
                   text);

  // The JSON spelling (efc convert) reads back to the same value.
  const std::string json_text = efc::dsl::print_json(doc->value);
  efc::Diagnostics json_diags;
  auto from_json =
      efc::frontend::parse_positioned(json_text, "printed.json", kMaxDepth, json_diags);
  if (!from_json || from_json->value != doc->value)
    efc_fuzz::fail("print_json(doc) does not read back to doc:\n--- document\n" +
                       doc->value.dump(1) + "\n--- print_json\n" + json_text + "\n--- errors\n" +
                       diagnostics_text(json_diags),
                   text);

  // The shape checks and the structure checks, as read_json_text runs them.
  efc::Object obj;
  obj.file = "fuzz.efc";
  obj.base_dir = efc_fuzz::base_dir();
  obj.positions = doc->positions;
  efc::Diagnostics shape;
  efc::frontend::build_object(doc->value, obj, efc::ReadOptions{}, shape);
  efc_fuzz::check_diagnostics(shape, text, false, "build_object (DSL document)");
  if (shape.has_errors()) return;
  efc::Diagnostics checks;
  efc::check_structure(obj, checks);
  efc_fuzz::check_diagnostics(checks, text, false, "check_structure (DSL document)");
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
