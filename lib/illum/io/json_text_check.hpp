#pragma once
// Checks on JSON text that a parser's own messages cannot name, made before
// the text is parsed: nesting deeper than `max_depth` (a hostile file of a
// million '[' would overflow the stack of any recursive printer or reader)
// and numbers outside the range of a double ("1e999"). Each error is an
// InputError with the file, the field's path ("surfaces[2].polygon[0][1]")
// and the text as written. The scan keeps an explicit stack: no recursion.
// Syntax errors are left to the parser, which reports line and column.
#include <string>
#include <string_view>

namespace illum {

void check_json_text(std::string_view text, const std::string& file, int max_depth);

}  // namespace illum
