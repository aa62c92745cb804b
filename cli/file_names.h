// What the tools read from file names.
#pragma once

#include <string>

namespace cli {

// The extension of the file `path` names, dot included, in lower case ("" when there is none; a
// dot in a folder name does not count): output formats are chosen by it.
std::string lower_extension(const std::string& path);

}  // namespace cli
