#pragma once
// Decoding a codestream with an outside decoder (opj_decompress, grk_decompress) into an image, for
// tests that prove our streams from outside. The decoder's own output is kept in OUT.log and quoted
// in the error when it fails.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "imageio/read.h"

namespace test_support {

// Runs `tool -i FILE -o OUT EXTRA` and reads OUT (a PNG keeps 8/16 bits and alpha).
inline imageio::Image decode_with(const std::string& tool, const std::filesystem::path& file,
                                  const std::filesystem::path& out, const std::string& extra = "") {
  const std::string cmd =
      tool + " -i '" + file.string() + "' -o '" + out.string() + "' " + extra + " >'" + out.string() + ".log' 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    std::ifstream log(out.string() + ".log");
    std::stringstream ss;
    ss << log.rdbuf();
    throw std::runtime_error(tool + " failed on " + file.string() + ": " + ss.str());
  }
  return imageio::read_image(out.string());
}

}  // namespace test_support
