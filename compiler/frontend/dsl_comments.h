// Comments of a .efc file, attached to the statements they belong to, so
// `efc fmt` rewrites a file without losing any. A comment on its own line
// belongs to the statement that follows it; one at the end of a line, to the
// first statement that starts on that line. Statements are named by the JSON
// pointer of the key they set (parts and functions by their element).
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/frontend/dsl_lexer.h"

namespace efc::dsl {

struct CommentMap {
  std::map<std::string, std::vector<std::string>> leading;  // own-line comments before
  std::map<std::string, std::string> trailing;              // at the end of its first line
  std::vector<std::string> file_end;                        // after the last statement
  bool empty() const { return leading.empty() && trailing.empty() && file_end.empty(); }
  size_t size() const;
};

struct StatementStart {
  std::string pointer;
  int line = 0, col = 0;
  size_t offset = 0;
};

// `statements` in source order.
CommentMap attach_comments(const std::vector<Comment>& comments,
                           const std::vector<StatementStart>& statements);

}  // namespace efc::dsl
