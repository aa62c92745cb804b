#pragma once
#include <cstddef>
#include <vector>

#include "codec/t1/block_style.h"

namespace codec::t2 {

// Where a code-block's codeword splits into separately terminated segments, which a packet
// header must announce one length each (T.800 B.10.7.2). `pass` counts from 0 = the first coded
// pass (the cleanup pass of the most significant non-zero bit-plane).
//  - terminate_each_pass: every pass ends a segment (with or without bypass).
//  - bypass alone (D.6, Table D.9): passes 0..9 (the first four bit-planes) are one MQ segment;
//    from pass 10 on, each bit-plane's significance + refinement passes are one raw segment and
//    its cleanup pass one MQ segment, so segments end after passes 9, 11, 12, 14, 15, 17, 18, ...
//  - otherwise: one segment for the whole block, so no pass ends one early.
// An HT code-block (BlockCoder::Ht) has its own rule (T.814 Annex B): its passes come in HT sets
// of a cleanup pass, then SigProp and MagRef; each cleanup pass (0, 3, ...) is an HT cleanup
// segment, and the two refinement passes after it (1-2, 4-5, ...) one HT refinement segment; the
// style's EBCOT switches do not apply.
enum class BlockCoder { Ebcot, Ht };
bool segment_ends_after(const t1::BlockStyle& style, int pass, BlockCoder coder = BlockCoder::Ebcot);

// One length field of a packet header: a run of `passes` consecutive coding passes inside one
// codeword segment, carrying `bytes` bytes.
struct SegmentPiece {
  int passes;
  std::size_t bytes;
};

// Splits the passes first_pass .. first_pass+count-1 that one packet adds for a block into the
// pieces whose lengths the header signals, appended to `pieces`. `cumulative_length(i)` is the
// byte count needed to decode through pass i (T1's PassInfo::length), so a piece's bytes are the
// difference of two.
template <class CumulativeLength>
void split_into_segments(const t1::BlockStyle& style, int first_pass, int count, CumulativeLength cumulative_length,
                         BlockCoder coder, std::vector<SegmentPiece>& pieces) {
  auto before = [&](int pass) -> std::size_t { return pass == 0 ? 0 : cumulative_length(pass - 1); };
  int start = first_pass;
  const int end = first_pass + count;
  for (int pass = first_pass; pass < end; ++pass) {
    if (pass == end - 1 || segment_ends_after(style, pass, coder)) {
      pieces.push_back(SegmentPiece{pass + 1 - start, cumulative_length(pass) - before(start)});
      start = pass + 1;
    }
  }
}

template <class CumulativeLength>
std::vector<SegmentPiece> split_into_segments(const t1::BlockStyle& style, int first_pass, int count,
                                              CumulativeLength cumulative_length,
                                              BlockCoder coder = BlockCoder::Ebcot) {
  std::vector<SegmentPiece> pieces;
  split_into_segments(style, first_pass, count, cumulative_length, coder, pieces);
  return pieces;
}

}  // namespace codec::t2
