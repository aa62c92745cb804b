#pragma once
// Codestreams deeper than our encoder writes (it stops at 16 bits), made from its 8-bit ones by
// their markers: SIZ says up to 38 bits (signed or not), and QCD and QCC raise the guard bits and
// each band's exponent. That moves every coded bit-plane up by as many planes, since a block's top
// plane is Mb - 1 - P with Mb = G + epsilon_b - 1 (T.800 E-2) and the packet headers' P counts
// down from Mb: a reversible stream then holds its coefficients times 2^rise. An irreversible one
// keeps its exponents, and n bits more in SIZ scale every step size (E-3) by 2^n instead.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace test_support {

// `stream` with SIZ's component depths set to `precision` and QCD's and QCC's guard bits to
// `guard_bits` (-1: as they are), their reversible exponents raised by `exponent_rise`.
inline std::vector<std::uint8_t> deepened(std::vector<std::uint8_t> stream, int precision, bool is_signed,
                                          int guard_bits, int exponent_rise) {
  std::size_t pos = 2;  // after SOC
  bool siz = false, qcd = false;
  while (pos + 4 <= stream.size()) {
    const int marker = stream[pos] << 8 | stream[pos + 1];
    const std::size_t length = static_cast<std::size_t>(stream[pos + 2] << 8 | stream[pos + 3]);
    if (marker == 0xFF90) break;  // the first SOT ends the main header
    if (marker == 0xFF51) {       // Csiz at 38 (Table A.9), then Ssiz, XRsiz, YRsiz per component
      const int components = stream[pos + 38] << 8 | stream[pos + 39];
      for (int c = 0; c < components; ++c)
        stream[pos + 40 + 3 * static_cast<std::size_t>(c)] =
            static_cast<std::uint8_t>((precision - 1) | (is_signed ? 0x80 : 0));
      siz = true;
    }
    if (marker == 0xFF5C || marker == 0xFF5D) {
      // Sqcd (or Sqcc after QCC's one-byte Cqcc, fewer than 257 components): guard bits over the
      // style; then reversible SPqcd: epsilon_b << 3 (Tables A.27-A.30).
      const std::size_t at = pos + (marker == 0xFF5C ? 4 : 5);
      const int style = stream[at] & 0x1F;
      if (guard_bits >= 0) stream[at] = static_cast<std::uint8_t>(guard_bits << 5 | style);
      if (exponent_rise != 0) {
        EXPECT_EQ(style, 0) << "exponents are raised in reversible streams only";
        for (std::size_t k = at + 1; k < pos + 2 + length; ++k) {
          const int exponent = (stream[k] >> 3) + exponent_rise;
          EXPECT_LE(exponent, 31);
          stream[k] = static_cast<std::uint8_t>(exponent << 3);
        }
      }
      qcd = true;
    }
    pos += 2 + length;
  }
  EXPECT_TRUE(siz && qcd) << "no SIZ or QCD in the main header";
  return stream;
}

}  // namespace test_support
