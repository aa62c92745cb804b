#pragma once
#include <cstdint>
#include <vector>

#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// Progression order, SGcod's first byte (T.800 Table A.16).
enum class ProgressionOrder : std::uint8_t { LRCP = 0, RLCP = 1, RPCL = 2, PCRL = 3, CPRL = 4 };

// Wavelet filter, SPcod's last fixed byte (T.800 Table A.20).
enum class WaveletTransform : std::uint8_t { Irreversible9x7 = 0, Reversible5x3 = 1 };

// Precinct size of one resolution as exponents: the precinct is 2^ppx x 2^ppy (T.800 Table A.21).
struct PrecinctSize {
  unsigned ppx = 15;
  unsigned ppy = 15;
};

// The per-component part shared by COD and COC (SPcod / SPcoc, T.800 Table A.15).
struct CodingStyle {
  unsigned levels = 5;  // decomposition levels NL, 0..32
  // Code-block size exponents: blocks are 2^xcb x 2^ycb, 2 <= xcb, ycb <= 10, xcb + ycb <= 12.
  // The segment stores xcb - 2 and ycb - 2.
  unsigned xcb = 6;
  unsigned ycb = 6;
  std::uint8_t block_style = 0;  // code-block coding-pass options, bit flags of Table A.19
  WaveletTransform transform = WaveletTransform::Reversible5x3;
  // Empty: the default maximal precincts (2^15 x 2^15), and the "user precincts" bit (Scod/Scoc
  // bit 0) stays clear. Otherwise exactly levels + 1 entries, resolution 0 (the LL band) first;
  // exponents 0..15, and 0 only at resolution 0, since a higher resolution's precinct is split
  // into half-size code-block partitions per subband.
  std::vector<PrecinctSize> precincts;
};

// Coding style default (T.800 A.6.1).
struct Cod {
  bool sop = false;  // Scod bit 1: SOP marker segments may precede packets
  bool eph = false;  // Scod bit 2: EPH markers follow packet headers
  ProgressionOrder order = ProgressionOrder::LRCP;
  unsigned layers = 1;  // 1..65535
  bool mct = false;     // multiple component transform on components 0, 1, 2 (Table A.17)
  CodingStyle style;
};

// Coding style component (T.800 A.6.2): overrides the COD's CodingStyle for one component.
struct Coc {
  unsigned component = 0;
  CodingStyle style;
};

// Throws CodestreamError unless every field of the style lies in the range T.800 allows. `who`
// names the segment ("COD", "COC 2") in messages.
void validate_coding_style(const CodingStyle& style, const char* who);

// Throw CodestreamError unless the segment's fields are in range; the writers below call these.
void validate_cod(const Cod& cod);
void validate_coc(const Coc& coc, unsigned num_components);

// Validate, then write the segment. Lcod = 12 + (levels + 1 when precincts are given).
void write_cod(ByteWriter& out, const Cod& cod);

// `num_components` is Csiz: Ccoc is one byte when Csiz < 257, two bytes otherwise (Table A.23),
// so Lcoc = 9 or 10, plus the precinct bytes.
void write_coc(ByteWriter& out, const Coc& coc, unsigned num_components);

}  // namespace codec::cs
