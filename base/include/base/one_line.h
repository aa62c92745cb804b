// Every failure reaches the user as exactly one line, whatever the messages it relays contain.
#pragma once

#include <string>
#include <string_view>

namespace base {

// Folds each run of line breaks (and the blanks around it) into "; " and drops leading and
// trailing breaks, so a multi-line library message or a path with a newline prints as one line.
std::string one_line(std::string_view text);

}  // namespace base
