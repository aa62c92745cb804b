#pragma once
#include <optional>
#include <vector>

#include "codec/codestream/byte_writer.h"
#include "codec/codestream/cod.h"
#include "codec/codestream/com.h"
#include "codec/codestream/qcd.h"
#include "codec/codestream/siz.h"

namespace codec::cs {

// Everything the main header says (T.800 A.3): SOC, SIZ, COD, COCs, QCD, QCCs, COMs. A component
// without a COC uses the COD's CodingStyle; one without a QCC uses the QCD.
struct MainHeader {
  Siz siz;
  Cod cod;
  std::vector<Coc> cocs;  // at most one per component
  Quantization qcd;
  std::vector<Qcc> qccs;  // at most one per component
  std::vector<Comment> comments;
  // Part 15 (HTJ2K, T.814 A.3): Ccap15, written in a CAP marker segment (Pcap with only bit 15's
  // capability set) right after the SIZ. The SIZ's Rsiz must then have bit 14 set (capabilities
  // in CAP). Absent: no CAP segment.
  std::optional<std::uint16_t> ccap15;
};

// Ccap15 for a codestream whose code-blocks are all HT blocks coded with one HT set (HTONLY,
// SINGLEHT, RGNFREE, HOMOGENEOUS; T.814 Table A.4): bit 5 when an irreversible transform may be
// used, and in bits 0-4 the MAGB field for the largest Mb (magnitude bit-planes) of any code-block.
std::uint16_t ht_only_ccap15(bool irreversible, int largest_magnitude_bitplanes);

// Rsiz bit 14: the codestream's capabilities are given in a CAP marker segment.
inline constexpr std::uint16_t kRsizCapabilitiesInCap = 0x4000;

// The coding style and quantization that apply to `component` in the main header.
const CodingStyle& coding_style_for(const MainHeader& h, unsigned component);
const Quantization& quantization_for(const MainHeader& h, unsigned component);

// Checks each segment on its own and the relations between them: COC/QCC components exist and are
// not repeated, every component's step count matches its decomposition levels (3 * levels + 1
// unless derived), and the multiple component transform has three components of equal
// subsampling and one wavelet filter among components 0-2, which selects RCT or ICT (T.800 G.2,
// G.3). Beyond T.800, it also requires one level count among components 0-2 under the transform,
// since OpenJPEG 2.5 cannot decode anything else. Throws CodestreamError on the first problem.
void validate_main_header(const MainHeader& h);

// Validates, then appends SOC SIZ COD COC... QCD QCC... COM...; nothing is appended on failure.
void write_main_header(ByteWriter& out, const MainHeader& h);

}  // namespace codec::cs
