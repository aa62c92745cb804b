// What one dwtool run is asked to do: the command line as typed (RawOptions) and the same request
// checked and turned into engine types (Request).
#pragma once

#include <optional>
#include <string>

#include "dwt/params.h"
#include "glcontext/context.h"

namespace dwtool {

enum class Direction { Forward, Inverse };
enum class BackendKind { Cpu, Gpu };

// Names stay text here: CLI11 only splits the command line, and resolve() reports bad values as
// dwtool's own one-line runtime errors, with the messages of the libraries that own the names.
struct RawOptions {
  Direction direction = Direction::Forward;
  std::string input;
  std::string output;
  std::string kernel = "97";
  int levels = 5;
  std::string boundary = "sym";
  std::string backend = "cpu";
  std::string origin = "0,0";
  int threads = 0;
  int bits = 8;
  std::string gl;  // empty: GPUJ2K_GL decides (only read when the GPU backend is used)
  bool quiet = false;
};

struct Request {
  Direction direction = Direction::Forward;
  std::string input;
  std::string output;
  dwt::DwtParams params;
  BackendKind backend = BackendKind::Cpu;
  int threads = 0;
  int bits = 8;
  std::optional<glc::Platform> gl;  // unset: glc::platform_from_env()
  bool quiet = false;
};

// Throws std::exception with a one-line message for any value that cannot be used.
Request resolve(const RawOptions& raw);

// "X,Y": two non-negative decimal integers and nothing else (no signs, spaces or empty parts).
dwt::Origin parse_origin(const std::string& text);

}  // namespace dwtool
