#pragma once
// gpuj2k: what the encoder (gpuj2k/encoder.h) and the decoder (gpuj2k/decoder.h) share: the one
// error type, how samples are laid out in the caller's memory, where the DWT runs, the version.
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

#if defined(_WIN32)
#define GPUJ2K_API
#else
#define GPUJ2K_API __attribute__((visibility("default")))
#endif

namespace gpuj2k {

// The library's one error type: invalid arguments, unreadable, unwritable or malformed files,
// images the standard cannot code, cancellation. The message is one line that names the parameter
// or file and the problem.
class GPUJ2K_API Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// How samples are stored in the caller's memory.
enum class SampleType {
  UInt8,   // unsigned, 1..8 significant bits
  UInt16,  // unsigned, 1..16 significant bits (native byte order)
  Int16,   // signed, 1..16 significant bits (native byte order)
  Int32,   // signed or unsigned, up to 31 bits (native byte order)
};

enum class Layout {
  Interleaved,  // the components of a pixel side by side, pixels in rows
  Planar,       // each component a plane of rows, planes one after another
};

// A JP2/JPH resolution (T.800 I.5.3.7, the capture and display resolution boxes): points per
// metre of the reference grid, vertically and horizontally; both 0 where there is none.
struct GridResolution {
  double vertical = 0, horizontal = 0;
  bool given() const { return vertical > 0 && horizontal > 0; }
};

enum class DwtDevice {
  Auto,  // a hardware GPU where it is faster for the image size, never a software renderer
  Cpu,
  Gpu,  // fails if no GL context can be made
};

// Worker threads and, where the DWT runs on the GPU, a GL context, that several encodes share as
// the caller chooses: give them the same engine (EncodeOptions::engine). An engine is made once and
// used from any thread; encodes running at once take turns on its workers and its context. Without
// one, each encode makes its own threads (and context) and drops them when it ends, which costs a
// few milliseconds for threads and tens to hundreds for a GL context.
class GPUJ2K_API Engine {
 public:
  explicit Engine(int threads = 0);  // 0: one per hardware thread
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  int threads() const;

  struct State;  // the library's own
  State& state() const { return *state_; }

 private:
  std::unique_ptr<State> state_;
};

// The library's version, "MAJOR.MINOR.PATCH".
GPUJ2K_API std::string version();

}  // namespace gpuj2k
