#pragma once
#include "codec/t1/block_style.h"

namespace codec::t1 {

// The order of coding passes (T.800 D.3, D.4, D.6) as pure functions of the pass index, so that
// the encoder's driver and anything that must agree with it (a decoder, a rate allocator) share
// one definition. Pass 0 is the cleanup pass of the most significant bit-plane in use; then each
// plane below gets significance propagation, magnitude refinement and cleanup.

enum class PassKind { Significance, Refinement, Cleanup };

inline int pass_count(int planes) { return planes > 0 ? 3 * planes - 2 : 0; }

inline PassKind pass_kind(int pass) {
  if (pass == 0) return PassKind::Cleanup;
  switch ((pass - 1) % 3) {
    case 0:
      return PassKind::Significance;
    case 1:
      return PassKind::Refinement;
    default:
      return PassKind::Cleanup;
  }
}

// The bit-plane a pass codes, counted from the least significant (0).
inline int pass_plane(int pass, int planes) { return planes - 1 - (pass + 2) / 3; }

// Selective arithmetic coding bypass (D.6): once the four most significant planes in use are
// coded (10 passes), significance and refinement passes are written raw; cleanup stays MQ coded.
inline bool pass_is_raw(int pass, const BlockStyle& s) {
  return s.bypass && pass >= 10 && pass_kind(pass) != PassKind::Cleanup;
}

// Whether the codeword segment ends after this pass (T.800 D.4, D.6): always after the last pass; after every pass with
// "terminate each pass"; with bypass, wherever the next pass switches between arithmetic and raw coding.
inline bool pass_ends_segment(int pass, int count, const BlockStyle& s) {
  if (pass == count - 1 || s.terminate_each_pass) return true;
  return s.bypass && pass_is_raw(pass, s) != pass_is_raw(pass + 1, s);
}

}  // namespace codec::t1
