#pragma once
#include <cstddef>
#include <vector>

#include "codec/tier2/header_bit_writer.h"

namespace codec::t2 {

// Tag-tree encoder (T.800 B.10.2). A tag tree codes a 2-D array of non-negative integers
// (one per code-block of a precinct's subband) hierarchically: each level halves the one below,
// rounding up, until a single root remains, and every node holds the minimum of the up to four
// nodes under it. A leaf is coded against a threshold t, walking from the root down: each node
// on the path sends 0 for "my value is above the current lower bound" (the bound then rises by
// one) and 1 for "my value equals it", and stops once the bound reaches t. What a node has sent
// is remembered, so later queries (higher thresholds, neighbouring leaves) send only what the
// decoder does not yet know. Packet headers use two trees per subband and precinct: inclusion
// (value: the first layer a code-block contributes to, threshold layer+1) and zero bit-planes
// (value: missing MSBs, coded completely on first inclusion).
class TagTreeEncoder {
 public:
  TagTreeEncoder() = default;
  // `leaf_values` in raster order, width*height of them, each >= 0. Width or height may be 0
  // (an empty tree, which is never queried).
  TagTreeEncoder(int width, int height, std::vector<int> leaf_values);

  int width() const { return width_; }
  int height() const { return height_; }
  int value(int x, int y) const;

  // Sends what a decoder needs to learn whether leaf (x, y) is below `threshold` and, if it is,
  // its exact value.
  void encode(int x, int y, int threshold, HeaderBitWriter& out);
  // Sends the leaf's value completely (threshold value+1).
  void encode_value(int x, int y, HeaderBitWriter& out);

 private:
  struct Node {
    int value = 0;
    int low = 0;         // lower bound the decoder already knows
    bool known = false;  // the decoder knows value == low
  };
  struct Level {
    int width, height;
    std::size_t offset;  // index of the level's first node in nodes_
  };
  std::size_t index(int level, int x, int y) const {
    const Level& lv = levels_[static_cast<std::size_t>(level)];
    return lv.offset + static_cast<std::size_t>(y) * static_cast<std::size_t>(lv.width) + static_cast<std::size_t>(x);
  }

  int width_ = 0, height_ = 0;
  std::vector<Level> levels_;  // levels_[0] = leaves, levels_.back() = root
  std::vector<Node> nodes_;
};

}  // namespace codec::t2
