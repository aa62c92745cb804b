#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/encoder/params.h"
#include "codec/encoder/source_image.h"

namespace codec {

// A raw codestream, a JP2 file (T.800 Annex I) or a JPH file (T.814 Annex D, for HT codestreams).
enum class FileFormat { Codestream, Jp2, Jph };

// Milliseconds spent in each stage of one encode (the thesis' Table 4.1 split, finer). GPU stages
// are measured with a glFinish before each clock read, so they are real, not estimates.
struct StageTimes {
  double setup = 0;           // planning, thread pools and DWT backends (less the GL times below)
  double gl_context = 0;      // creating the GL context (GPU DWT only)
  double shader_compile = 0;  // compiling the DWT shader (GPU DWT only)
  double level_shift = 0;     // DC level shift and component transform
  double upload = 0;          // planes to the GPU
  double dwt = 0;             // the transform itself
  double download = 0;        // planes back from the GPU
  double tier1 = 0;           // tier-1, which quantises lossy code-blocks as it loads them
  double rate_control = 0;    // hulls, allocation, and the trial assemblies that size the file
  double tier2 = 0;           // the final packets and codestream
  // Freeing the coefficients, code-blocks and given-up source samples (a 4096x4096 RGB encode's
  // 250 MB of planes take some 20 ms to hand back, the kernel's work per page), a GL context made
  // for this image, and the encode's own worker threads.
  double release = 0;
  double total() const {
    return setup + gl_context + shader_compile + level_shift + upload + dwt + download + tier1 + rate_control + tier2 +
           release;
  }
};

// What an encode tells its caller besides the bytes.
struct EncodeReport {
  StageTimes times;
  int threads = 0;
  std::string dwt_backend;           // the backend that ran the DWT, with its renderer for the GPU
  std::string dwt_reason;            // why that backend (--dwt auto's decision, or what was asked)
  std::vector<std::string> notices;  // one line each, e.g. the GPU fallback
  std::size_t recoded_blocks = 0;    // pass skipping: blocks coded again after allocation (a block may count twice)
  double base_step = 0;              // lossy: the base step quantised with (EncodeParams::ht_step_from_target)
};

// Encodes an image to a JPEG 2000 codestream (.j2k) or a JP2 file. Throws EncodeError.
std::vector<std::uint8_t> encode(const SourceImage& image, const EncodeParams& params, FileFormat format,
                                 EncodeReport* report = nullptr);

// The same, for a caller that no longer needs the samples, when one tile covers the whole image: a
// lossless encode transforms them in place instead of copying them, a lossy one (without PSNR
// targets) releases them row by row as it converts them to floats; either way one image's worth of
// memory less. Afterwards the image keeps its size and components, but its samples may be gone.
std::vector<std::uint8_t> encode(SourceImage&& image, const EncodeParams& params, FileFormat format,
                                 EncodeReport* report = nullptr);

}  // namespace codec
