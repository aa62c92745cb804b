// Encodes a 256x256 RGB gradient from memory at 1 bit per pixel and writes the codestream.
#include <gpuj2k/encoder.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: encode_buffer OUT.j2k\n"), 2;
  std::vector<std::uint8_t> rgb(256 * 256 * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i)
    rgb[i] = static_cast<std::uint8_t>((i / 3 % 256) ^ (i / 768) ^ (i % 3 * 85));
  gpuj2k::ImageView image;
  image.data = rgb.data();
  image.size_bytes = rgb.size();
  image.width = image.height = 256;
  image.components = 3;
  gpuj2k::EncodeOptions options;
  options.rates_bpp = {1.0};
  try {
    const std::vector<std::uint8_t> j2k = gpuj2k::encode(image, options);
    std::ofstream(argv[1], std::ios::binary)
        .write(reinterpret_cast<const char*>(j2k.data()), static_cast<std::streamsize>(j2k.size()));
    std::printf("%s: %zu bytes (gpuj2k %s)\n", argv[1], j2k.size(), gpuj2k::version().c_str());
  } catch (const gpuj2k::Error& e) {
    std::fprintf(stderr, "encode_buffer: %s\n", e.what());
    return 1;
  }
}
