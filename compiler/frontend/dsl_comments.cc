#include "compiler/frontend/dsl_comments.h"

#include <algorithm>

namespace efc::dsl {

size_t CommentMap::size() const {
  size_t n = trailing.size() + file_end.size();
  for (const auto& [p, lines] : leading) n += lines.size();
  return n;
}

CommentMap attach_comments(const std::vector<Comment>& comments,
                           const std::vector<StatementStart>& statements) {
  CommentMap map;
  for (const Comment& c : comments) {
    if (!c.own_line) {
      auto first_on_line = std::find_if(statements.begin(), statements.end(),
                                        [&](const StatementStart& s) { return s.line == c.line; });
      if (first_on_line != statements.end() && !map.trailing.count(first_on_line->pointer)) {
        map.trailing[first_on_line->pointer] = c.text;
        continue;
      }
    }
    // Own line (or a line with no statement start, such as a closing '}'):
    // before the next statement.
    auto next = std::find_if(statements.begin(), statements.end(),
                             [&](const StatementStart& s) { return s.line > c.line; });
    if (next != statements.end())
      map.leading[next->pointer].push_back(c.text);
    else
      map.file_end.push_back(c.text);
  }
  return map;
}

}  // namespace efc::dsl
