#pragma once

#include <cstddef>
#include <string>

#include "imageio/image.h"

// OpenImageIO is loaded on demand. Linked into every program, it brought about 260 shared
// libraries (OpenCV, FFmpeg, DCMTK, ...) whose symbol binding cost each process about 0.2 s
// before main() did anything, which was most of an encode of a small image. PFM and Netpbm never
// need it, so the OpenImageIO reader and writer are built as a module (libgpuj2k_imageio_oiio.so,
// next to the programs) that the first PNG, TIFF, EXR, ... opens with dlopen().

namespace imageio::detail {

// The module's entry points, C linkage so dlsym finds them by these names. Each returns
// kModuleOk, or kModuleFailed with a one-line problem (without the path) in `problem`, a buffer
// of `problem_size` bytes. Both run in the same process with the same C++ runtime, so the Image
// crosses as it is; exceptions do not cross.
inline constexpr int kModuleOk = 0;
inline constexpr int kModuleFailed = 1;
inline constexpr const char* kReadSymbol = "gpuj2k_oiio_read";
inline constexpr const char* kWriteSymbol = "gpuj2k_oiio_write";
using ModuleRead = int (*)(const char* path, Image* image, char* problem, std::size_t problem_size);
using ModuleWrite = int (*)(const char* path, const Image* image, char* problem, std::size_t problem_size);

// Read and write through the module, loading it on first use. The module is looked for at
// $GPUJ2K_OIIO_MODULE when that is set, else next to the running program, else by the dynamic
// loader's own search. Throws IoError(path, ...) when it cannot be loaded or the file fails.
Image read_through_module(const std::string& path);
void write_through_module(const std::string& path, const Image& image);

}  // namespace imageio::detail
