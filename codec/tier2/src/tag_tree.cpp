#include "codec/tier2/tag_tree.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace codec::t2 {

TagTreeEncoder::TagTreeEncoder(int width, int height, std::vector<int> leaf_values) : width_(width), height_(height) {
  if (width < 0 || height < 0) throw std::invalid_argument("TagTreeEncoder: negative size");
  if (leaf_values.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("TagTreeEncoder: leaf count does not match width*height");
  if (width == 0 || height == 0) return;

  // Level sizes: halve (rounding up) until 1x1. A 1x1 array is its own root.
  std::size_t total = 0;
  int w = width, h = height;
  for (;;) {
    levels_.push_back(Level{w, h, total});
    total += static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (w == 1 && h == 1) break;
    w = (w + 1) / 2;
    h = (h + 1) / 2;
  }
  nodes_.resize(total);
  for (std::size_t i = 0; i < leaf_values.size(); ++i) {
    if (leaf_values[i] < 0) throw std::invalid_argument("TagTreeEncoder: negative leaf value");
    nodes_[i].value = leaf_values[i];
  }
  // Each parent holds the minimum of its children; children (x, y) map to parent (x/2, y/2).
  for (std::size_t l = 1; l < levels_.size(); ++l) {
    const Level& parent = levels_[l];
    for (std::size_t i = 0; i < static_cast<std::size_t>(parent.width) * parent.height; ++i)
      nodes_[parent.offset + i].value = std::numeric_limits<int>::max();
    const Level& child = levels_[l - 1];
    for (int y = 0; y < child.height; ++y)
      for (int x = 0; x < child.width; ++x) {
        int& v = nodes_[index(static_cast<int>(l), x / 2, y / 2)].value;
        v = std::min(v, nodes_[index(static_cast<int>(l) - 1, x, y)].value);
      }
  }
}

int TagTreeEncoder::value(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) throw std::out_of_range("TagTreeEncoder: leaf outside the tree");
  return nodes_[index(0, x, y)].value;
}

void TagTreeEncoder::encode(int x, int y, int threshold, HeaderBitWriter& out) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) throw std::out_of_range("TagTreeEncoder: leaf outside the tree");
  // Root first. A node's bound starts where its parent's ended: the parent is the minimum of its
  // children, so the decoder already knows every child is at least that large.
  int parent_low = 0;
  for (int level = static_cast<int>(levels_.size()) - 1; level >= 0; --level) {
    Node& node = nodes_[index(level, x >> level, y >> level)];
    if (node.low < parent_low) node.low = parent_low;
    while (!node.known && node.low < threshold) {
      if (node.low >= node.value) {
        out.put_bit(true);
        node.known = true;
      } else {
        out.put_bit(false);
        ++node.low;
      }
    }
    parent_low = node.low;
  }
}

void TagTreeEncoder::encode_value(int x, int y, HeaderBitWriter& out) {
  const int v = value(x, y);
  if (v == std::numeric_limits<int>::max())
    throw std::invalid_argument("TagTreeEncoder: value too large to code completely");
  encode(x, y, v + 1, out);
}

}  // namespace codec::t2
