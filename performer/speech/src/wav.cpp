#include "performer/wav.h"

#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "base/atomic_file.h"

namespace performer {

namespace {

// The canonical 44-byte header: RIFF chunk header, "WAVE", a 16-byte "fmt " chunk, "data" header.
constexpr std::size_t kHeaderBytes = 44;
constexpr std::uint16_t kFormatPcm = 1;
constexpr std::uint16_t kBitsPerSample = 16;
constexpr std::uint16_t kBlockAlign = 2;  // one 16-bit channel
// RIFF sizes are 32-bit and count everything after the first 8 bytes.
constexpr std::uint64_t kMaxDataBytes = 0xFFFFFFFFull - (kHeaderBytes - 8);

// WAV is little-endian whatever the machine is: bytes are placed one by one.
void put_u16(std::string& out, std::uint16_t value) {
  out += static_cast<char>(value & 0xFF);
  out += static_cast<char>(value >> 8);
}

void put_u32(std::string& out, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((value >> shift) & 0xFF);
}

std::uint16_t get_u16(std::string_view bytes, std::size_t pos) {
  return static_cast<std::uint16_t>(static_cast<unsigned char>(bytes[pos]) | static_cast<unsigned char>(bytes[pos + 1])
                                                                                 << 8);
}

std::uint32_t get_u32(std::string_view bytes, std::size_t pos) {
  return static_cast<std::uint32_t>(get_u16(bytes, pos)) | static_cast<std::uint32_t>(get_u16(bytes, pos + 2)) << 16;
}

std::string encode_wav(int sample_rate, std::span<const std::int16_t> samples) {
  const auto data_bytes = static_cast<std::uint32_t>(samples.size() * 2);
  const auto rate = static_cast<std::uint32_t>(sample_rate);
  std::string out;
  out.reserve(kHeaderBytes + data_bytes);
  out += "RIFF";
  put_u32(out, static_cast<std::uint32_t>(kHeaderBytes - 8) + data_bytes);
  out += "WAVE";
  out += "fmt ";
  put_u32(out, 16);
  put_u16(out, kFormatPcm);
  put_u16(out, 1);  // channels
  put_u32(out, rate);
  put_u32(out, rate * kBlockAlign);  // bytes per second
  put_u16(out, kBlockAlign);
  put_u16(out, kBitsPerSample);
  out += "data";
  put_u32(out, data_bytes);
  for (const std::int16_t s : samples) put_u16(out, static_cast<std::uint16_t>(s));
  return out;
}

std::runtime_error bad_file(const std::filesystem::path& file, const std::string& problem) {
  return std::runtime_error(file.string() + ": " + problem);
}

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw bad_file(file, "cannot open");
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw bad_file(file, "read error");
  return bytes;
}

// Checks the "fmt " chunk body and returns the sample rate.
int read_format(std::string_view body, const std::filesystem::path& file) {
  if (body.size() < 16) throw bad_file(file, "\"fmt \" chunk is " + std::to_string(body.size()) + " bytes, need 16");
  const std::uint16_t format = get_u16(body, 0);
  const std::uint16_t channels = get_u16(body, 2);
  const std::uint32_t rate = get_u32(body, 4);
  const std::uint32_t byte_rate = get_u32(body, 8);
  const std::uint16_t block_align = get_u16(body, 12);
  const std::uint16_t bits = get_u16(body, 14);
  if (format != kFormatPcm || channels != 1 || bits != kBitsPerSample)
    throw bad_file(file, "not 16-bit mono PCM (format " + std::to_string(format) + ", " + std::to_string(channels) +
                             " channel(s), " + std::to_string(bits) + " bits)");
  if (rate == 0 || rate > 0x7FFFFFFF) throw bad_file(file, "sample rate " + std::to_string(rate) + " is invalid");
  if (block_align != kBlockAlign || byte_rate != rate * kBlockAlign)
    throw bad_file(file, "block align or byte rate disagrees with 16-bit mono at " + std::to_string(rate) + " Hz");
  return static_cast<int>(rate);
}

std::vector<std::int16_t> read_samples(std::string_view body, const std::filesystem::path& file) {
  if (body.size() % kBlockAlign != 0)
    throw bad_file(file, "\"data\" chunk of " + std::to_string(body.size()) + " bytes is not whole samples");
  std::vector<std::int16_t> samples(body.size() / kBlockAlign);
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = static_cast<std::int16_t>(get_u16(body, 2 * i));
  return samples;
}

}  // namespace

void write_wav(const std::filesystem::path& file, int sample_rate, std::span<const std::int16_t> samples) {
  if (sample_rate <= 0)
    throw std::invalid_argument("WAV sample rate " + std::to_string(sample_rate) + " is not positive");
  if (samples.size() * 2 > kMaxDataBytes)
    throw std::invalid_argument("WAV cannot hold " + std::to_string(samples.size()) + " samples (32-bit sizes)");
  base::replace_file_atomically(file.string(), encode_wav(sample_rate, samples));
}

WavAudio read_wav(const std::filesystem::path& file) {
  const std::string bytes = read_bytes(file);
  const std::string_view all(bytes);
  if (all.size() < 12 || all.substr(0, 4) != "RIFF" || all.substr(8, 4) != "WAVE")
    throw bad_file(file, "not a RIFF/WAVE file");
  if (static_cast<std::uint64_t>(get_u32(all, 4)) + 8 != all.size())
    throw bad_file(file, "RIFF header says " + std::to_string(get_u32(all, 4) + 8ull) + " bytes, the file has " +
                             std::to_string(all.size()));
  std::optional<int> rate;
  // Chunks: 4-byte ID, 32-bit size, body padded to an even length.
  for (std::size_t pos = 12; pos < all.size();) {
    if (all.size() - pos < 8) throw bad_file(file, "truncated chunk header at byte " + std::to_string(pos));
    const std::string_view id = all.substr(pos, 4);
    const std::uint32_t size = get_u32(all, pos + 4);
    if (size > all.size() - pos - 8)
      throw bad_file(file, "chunk \"" + std::string(id) + "\" runs past the end of the file");
    const std::string_view body = all.substr(pos + 8, size);
    if (id == "fmt ") rate = read_format(body, file);
    if (id == "data") {
      if (!rate) throw bad_file(file, "\"data\" chunk before the \"fmt \" chunk");
      return {*rate, read_samples(body, file)};
    }
    pos += 8 + size + (size & 1);
  }
  throw bad_file(file, "no \"data\" chunk");
}

}  // namespace performer
