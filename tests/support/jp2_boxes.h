#pragma once
// JP2 files built box by box around a codestream (T.800 Annex I), for tests of what a JP2 reader
// does with the boxes our encoder never writes (palettes, channel definitions, ICC profiles).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace test_support {

// One box: its length (8 + body), its four-letter type, its body.
inline std::vector<std::uint8_t> box(const char* type, const std::vector<std::uint8_t>& body) {
  const auto length = static_cast<std::uint32_t>(body.size() + 8);
  std::vector<std::uint8_t> out(8 + body.size());
  for (int i = 0; i < 4; ++i) {
    out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(length >> (24 - 8 * i));
    out[static_cast<std::size_t>(4 + i)] = static_cast<std::uint8_t>(type[i]);
  }
  std::copy(body.begin(), body.end(), out.begin() + 8);
  return out;
}

// A JP2 file around `codestream` (I.4, I.5): signature, ftyp, jp2h with `header_boxes`, jp2c.
inline std::vector<std::uint8_t> jp2_file(const std::vector<std::uint8_t>& codestream,
                                          const std::vector<std::vector<std::uint8_t>>& header_boxes) {
  std::vector<std::uint8_t> out{0, 0, 0, 0x0C, 'j', 'P', ' ', ' ', 0x0D, 0x0A, 0x87, 0x0A};
  for (const auto& b : {box("ftyp", {'j', 'p', '2', ' ', 0, 0, 0, 0, 'j', 'p', '2', ' '})})
    out.insert(out.end(), b.begin(), b.end());
  std::vector<std::uint8_t> header;
  for (const auto& b : header_boxes) header.insert(header.end(), b.begin(), b.end());
  for (const auto& b : {box("jp2h", header), box("jp2c", codestream)}) out.insert(out.end(), b.begin(), b.end());
  return out;
}

// An image header box (I.5.3.1), the first box a jp2h must hold: size, components, bits per
// component (unsigned), compression type 7, colour space known, no intellectual property box.
inline std::vector<std::uint8_t> ihdr(std::uint32_t width, std::uint32_t height, std::uint16_t components, int bits) {
  std::vector<std::uint8_t> body(14, 0);
  for (int i = 0; i < 4; ++i) {
    body[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(height >> (24 - 8 * i));
    body[static_cast<std::size_t>(4 + i)] = static_cast<std::uint8_t>(width >> (24 - 8 * i));
  }
  body[8] = static_cast<std::uint8_t>(components >> 8);
  body[9] = static_cast<std::uint8_t>(components);
  body[10] = static_cast<std::uint8_t>(bits - 1);
  body[11] = 7;
  return box("ihdr", body);
}

// A made-up ICC profile of `size` bytes (at least 132): the ICC.1 header's fields a reader looks
// at (size, version 4.3, a display-class RGB profile to XYZ, the 'acsp' signature, the D50 PCS
// illuminant), no tags, then
// filler bytes that differ from place to place, so that a copy that loses or moves any shows.
inline std::vector<std::uint8_t> made_up_icc_profile(std::uint32_t size) {
  std::vector<std::uint8_t> p(size, 0);
  auto put = [&](std::size_t at, const char* four) {
    for (int i = 0; i < 4; ++i) p[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(four[i]);
  };
  for (int i = 0; i < 4; ++i) p[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(size >> (24 - 8 * i));
  p[8] = 0x04;
  p[9] = 0x30;
  put(12, "mntr");
  put(16, "RGB ");
  put(20, "XYZ ");
  put(36, "acsp");
  // The PCS illuminant, D50 in s15Fixed16 (ICC.1 7.2.16): libpng checks it.
  const std::uint32_t d50[3] = {0x0000F6D6, 0x00010000, 0x0000D32D};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 4; ++i)
      p[static_cast<std::size_t>(68 + 4 * k + i)] = static_cast<std::uint8_t>(d50[k] >> (24 - 8 * i));
  for (std::size_t i = 132; i < size; ++i) p[i] = static_cast<std::uint8_t>((i * 7) % 251);
  return p;
}

// A colr box body (I.5.3.3) with METH 2 (restricted ICC) and `profile`.
inline std::vector<std::uint8_t> icc_colr(const std::vector<std::uint8_t>& profile) {
  std::vector<std::uint8_t> body(3 + profile.size(), 0);  // METH, PREC, APPROX, then the profile
  body[0] = 2;
  std::copy(profile.begin(), profile.end(), body.begin() + 3);
  return body;
}

}  // namespace test_support
