#pragma once
// An independent tier-1 decoder for the tests, written from T.800 Annex C (MQ decoder, C.3) and
// Annex D (decoding passes) without the encoder's tables or state layout: plain per-coefficient
// arrays, neighbourhoods counted on the spot with bounds checks, contexts chosen by if-chains
// that follow the standard's tables row by row. Slow on purpose; clarity is the point.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "codec/t1/block_style.h"

namespace t1ref {

// ---------------------------------------------------------------------------------------------
// MQ decoder (T.800 C.3). Probability table typed in again from T.800 Table C.2.
struct QeRow {
  unsigned qe;
  int nmps;
  int nlps;
  int switch_mps;
};

inline const QeRow kQeTable[47] = {
    {0x5601, 1, 1, 1},   {0x3401, 2, 6, 0},   {0x1801, 3, 9, 0},   {0x0AC1, 4, 12, 0},  {0x0521, 5, 29, 0},
    {0x0221, 38, 33, 0}, {0x5601, 7, 6, 1},   {0x5401, 8, 14, 0},  {0x4801, 9, 14, 0},  {0x3801, 10, 14, 0},
    {0x3001, 11, 17, 0}, {0x2401, 12, 18, 0}, {0x1C01, 13, 20, 0}, {0x1601, 29, 21, 0}, {0x5601, 15, 14, 1},
    {0x5401, 16, 14, 0}, {0x5101, 17, 15, 0}, {0x4801, 18, 16, 0}, {0x3801, 19, 17, 0}, {0x3401, 20, 18, 0},
    {0x3001, 21, 19, 0}, {0x2801, 22, 19, 0}, {0x2401, 23, 20, 0}, {0x2201, 24, 21, 0}, {0x1C01, 25, 22, 0},
    {0x1801, 26, 23, 0}, {0x1601, 27, 24, 0}, {0x1401, 28, 25, 0}, {0x1201, 29, 26, 0}, {0x1101, 30, 27, 0},
    {0x0AC1, 31, 28, 0}, {0x09C1, 32, 29, 0}, {0x08A1, 33, 30, 0}, {0x0521, 34, 31, 0}, {0x0441, 35, 32, 0},
    {0x02A1, 36, 33, 0}, {0x0221, 37, 34, 0}, {0x0141, 38, 35, 0}, {0x0111, 39, 36, 0}, {0x0085, 40, 37, 0},
    {0x0049, 41, 38, 0}, {0x0025, 42, 39, 0}, {0x0015, 43, 40, 0}, {0x0009, 44, 41, 0}, {0x0005, 45, 42, 0},
    {0x0001, 45, 43, 0}, {0x5601, 46, 46, 0},
};

struct RefContext {
  int index = 0;
  int mps = 0;
};

class MqDecoder {
 public:
  MqDecoder() = default;
  explicit MqDecoder(std::span<const std::uint8_t> data) : data_(data) {
    // INITDEC (C.3.5)
    bp_ = 0;
    c_ = static_cast<std::uint32_t>(byte(0)) << 16;
    bytein();
    c_ <<= 7;
    ct_ -= 7;
    a_ = 0x8000;
  }

  // DECODE (C.3.2) with MPS_EXCHANGE / LPS_EXCHANGE (C.3.3) and RENORMD (C.3.4).
  int decode(RefContext& cx) {
    const QeRow& row = kQeTable[cx.index];
    a_ -= row.qe;
    int d;
    if ((c_ >> 16) < row.qe) {
      if (a_ < row.qe) {
        a_ = row.qe;
        d = cx.mps;
        cx.index = row.nmps;
      } else {
        a_ = row.qe;
        d = 1 - cx.mps;
        if (row.switch_mps) cx.mps = 1 - cx.mps;
        cx.index = row.nlps;
      }
      renormd();
    } else {
      c_ -= row.qe << 16;
      if ((a_ & 0x8000) == 0) {
        if (a_ < row.qe) {
          d = 1 - cx.mps;
          if (row.switch_mps) cx.mps = 1 - cx.mps;
          cx.index = row.nlps;
        } else {
          d = cx.mps;
          cx.index = row.nmps;
        }
        renormd();
      } else {
        d = cx.mps;
      }
    }
    return d;
  }

 private:
  // Past the end of the data the decoder sees 0xFF bytes, which BYTEIN treats as a marker:
  // from then on it feeds 1 bits.
  unsigned byte(std::size_t i) const { return i < data_.size() ? data_[i] : 0xFFu; }

  void bytein() {
    if (byte(bp_) == 0xFF) {
      if (byte(bp_ + 1) > 0x8F) {
        c_ += 0xFF00;
        ct_ = 8;
      } else {
        ++bp_;
        c_ += byte(bp_) << 9;
        ct_ = 7;
      }
    } else {
      ++bp_;
      c_ += byte(bp_) << 8;
      ct_ = 8;
    }
  }

  void renormd() {
    do {
      if (ct_ == 0) bytein();
      a_ <<= 1;
      c_ <<= 1;
      --ct_;
    } while ((a_ & 0x8000) == 0);
  }

  std::span<const std::uint8_t> data_;
  std::size_t bp_ = 0;
  std::uint32_t a_ = 0, c_ = 0;
  int ct_ = 0;
};

// Raw segment reader (T.800 D.6): MSB first; the MSB of a byte after 0xFF is a stuffed 0.
class RawReader {
 public:
  RawReader() = default;
  explicit RawReader(std::span<const std::uint8_t> data) : data_(data) {}
  int bit() {
    if (left_ == 0) {
      const bool after_ff = cur_ == 0xFF;
      cur_ = pos_ < data_.size() ? data_[pos_] : 0xFFu;
      ++pos_;
      left_ = after_ff ? 7 : 8;
    }
    --left_;
    return static_cast<int>((cur_ >> left_) & 1u);
  }

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  unsigned cur_ = 0;
  int left_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Tier-1 decoder (Annex D).
enum class Band { LL, HL, LH, HH };

class T1Decoder {
 public:
  // `segment_ends`: end offset in `data` of each codeword segment in turn (the last one may be a
  // truncation point). `planes` is the number of magnitude bit-planes coded (Mb - missing MSBs).
  T1Decoder(int width, int height, Band band, int planes, codec::t1::BlockStyle style,
            std::span<const std::uint8_t> data, std::vector<std::size_t> segment_ends)
      : w_(width),
        h_(height),
        band_(band),
        planes_(planes),
        style_(style),
        data_(data),
        segment_ends_(std::move(segment_ends)) {
    const auto n = static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_);
    sig_.assign(n, 0);
    neg_.assign(n, 0);
    refined_.assign(n, 0);
    mag_.assign(n, 0);
    known_.assign(n, 0);
    visited_.assign(n, -1);
    init_contexts();
  }

  int pass_total() const { return planes_ > 0 ? 3 * planes_ - 2 : 0; }

  // D.3: first a cleanup pass on the top plane, then SPP, MRP, CP on every plane below.
  static int kind_of(int pass) { return pass == 0 ? 2 : (pass - 1) % 3; }  // 0 SPP, 1 MRP, 2 CP
  int plane_of(int pass) const { return planes_ - 1 - (pass + 2) / 3; }
  // D.6: bypass leaves the SPP and MRP raw from the fifth plane down (after the first 10 passes).
  bool is_raw(int pass) const { return style_.bypass && pass >= 10 && kind_of(pass) != 2; }
  // Termination (D.4, D.6): after every pass with "terminate each pass"; with bypass after each cleanup
  // pass from the fourth plane on (pass 9 onwards) and after each raw refinement pass; and at the end.
  bool is_terminated(int pass) const {
    if (pass == pass_total() - 1 || style_.terminate_each_pass) return true;
    if (!style_.bypass) return false;
    if (kind_of(pass) == 2 && pass >= 9) return true;
    return kind_of(pass) == 1 && pass >= 10;
  }

  void decode_pass() {
    const int pass = next_pass_++;
    if (pass >= pass_total()) throw std::logic_error("no more passes");
    if (!segment_open_) open_segment(is_raw(pass));
    const int p = plane_of(pass);
    raw_ = is_raw(pass);
    switch (kind_of(pass)) {
      case 0:
        significance_pass(p);
        break;
      case 1:
        refinement_pass(p);
        break;
      default:
        cleanup_pass(p);
        if (style_.segmentation_symbols) {
          int symbol = 0;
          for (int i = 0; i < 4; ++i) symbol = (symbol << 1) | mq_.decode(cx_[kUniform]);
          if (symbol != 0xA) segmentation_errors_++;
        }
    }
    if (is_terminated(pass)) segment_open_ = false;
    if (style_.reset) init_contexts();
  }

  int segmentation_errors() const { return segmentation_errors_; }

  // Mid-point reconstruction: with planes >= p known, magnitude + 2^(p-1); exact once p = 0.
  std::vector<std::int64_t> reconstruction() const {
    std::vector<std::int64_t> out(sig_.size(), 0);
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (!sig_[i]) continue;
      std::int64_t m = mag_[i];
      if (known_[i] > 0) m += std::int64_t{1} << (known_[i] - 1);
      out[i] = neg_[i] ? -m : m;
    }
    return out;
  }

 private:
  static constexpr int kRunLength = 17;
  static constexpr int kUniform = 18;

  void init_contexts() {
    for (auto& c : cx_) c = RefContext{0, 0};
    cx_[0].index = 4;  // zero coding, all neighbours insignificant
    cx_[kRunLength].index = 3;
    cx_[kUniform].index = 46;
  }

  void open_segment(bool raw) {
    if (segment_index_ >= segment_ends_.size()) throw std::logic_error("more segments than lengths given");
    const std::size_t end = segment_ends_[segment_index_++];
    if (end < segment_begin_ || end > data_.size()) throw std::logic_error("bad segment end");
    const auto bytes = data_.subspan(segment_begin_, end - segment_begin_);
    if (raw)
      raw_reader_ = RawReader(bytes);
    else
      mq_ = MqDecoder(bytes);
    segment_begin_ = end;
    segment_open_ = true;
  }

  std::size_t at(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x);
  }

  // Whether neighbour (nx, ny) counts as significant for the coefficient on row y: outside the
  // block it does not; with vertically causal contexts (D.7) nor does anything in a later stripe.
  bool visible_sig(int nx, int ny, int y) const {
    if (nx < 0 || ny < 0 || nx >= w_ || ny >= h_) return false;
    if (style_.vertically_causal && ny / 4 > y / 4) return false;
    return sig_[at(nx, ny)] != 0;
  }

  void counts(int x, int y, int& h, int& v, int& d) const {
    h = visible_sig(x - 1, y, y) + visible_sig(x + 1, y, y);
    v = visible_sig(x, y - 1, y) + visible_sig(x, y + 1, y);
    d = visible_sig(x - 1, y - 1, y) + visible_sig(x + 1, y - 1, y) + visible_sig(x - 1, y + 1, y) +
        visible_sig(x + 1, y + 1, y);
  }

  // Table D.1.
  int zc_context(int x, int y) const {
    int h, v, d;
    counts(x, y, h, v, d);
    if (band_ == Band::HH) {
      const int hv = h + v;
      if (d >= 3) return 8;
      if (d == 2) return hv >= 1 ? 7 : 6;
      if (d == 1) {
        if (hv >= 2) return 5;
        if (hv == 1) return 4;
        return 3;
      }
      if (hv >= 2) return 2;
      if (hv == 1) return 1;
      return 0;
    }
    if (band_ == Band::HL) {
      const int t = h;
      h = v;
      v = t;
    }
    if (h == 2) return 8;
    if (h == 1 && v >= 1) return 7;
    if (h == 1 && v == 0 && d >= 1) return 6;
    if (h == 1) return 5;
    if (v == 2) return 4;
    if (v == 1) return 3;
    if (d >= 2) return 2;
    if (d == 1) return 1;
    return 0;
  }

  int contribution(int nx, int ny, int y) const {
    if (!visible_sig(nx, ny, y)) return 0;
    return neg_[at(nx, ny)] ? -1 : 1;
  }

  // Tables D.2 and D.3.
  int decode_sign(int x, int y) {
    if (raw_) return raw_reader_.bit();
    auto clamp = [](int s) { return s > 0 ? 1 : (s < 0 ? -1 : 0); };
    const int hc = clamp(contribution(x - 1, y, y) + contribution(x + 1, y, y));
    const int vc = clamp(contribution(x, y - 1, y) + contribution(x, y + 1, y));
    int ctx = 9, xorbit = 0;
    if (hc == 1 && vc == 1)
      ctx = 13;
    else if (hc == 1 && vc == 0)
      ctx = 12;
    else if (hc == 1 && vc == -1)
      ctx = 11;
    else if (hc == 0 && vc == 1)
      ctx = 10;
    else if (hc == 0 && vc == 0)
      ctx = 9;
    else if (hc == 0 && vc == -1) {
      ctx = 10;
      xorbit = 1;
    } else if (hc == -1 && vc == 1) {
      ctx = 11;
      xorbit = 1;
    } else if (hc == -1 && vc == 0) {
      ctx = 12;
      xorbit = 1;
    } else {
      ctx = 13;
      xorbit = 1;
    }
    return mq_.decode(cx_[ctx]) ^ xorbit;
  }

  int decode_bit(int ctx) { return raw_ ? raw_reader_.bit() : mq_.decode(cx_[ctx]); }

  void becomes_significant(int x, int y, int p) {
    const std::size_t i = at(x, y);
    neg_[i] = static_cast<std::uint8_t>(decode_sign(x, y));
    sig_[i] = 1;
    mag_[i] |= std::uint32_t{1} << p;
    known_[i] = p;
  }

  template <class F>
  void scan(F&& f) {
    for (int y0 = 0; y0 < h_; y0 += 4)
      for (int x = 0; x < w_; ++x)
        for (int y = y0; y < y0 + 4 && y < h_; ++y) f(x, y);
  }

  void significance_pass(int p) {
    scan([&](int x, int y) {
      const std::size_t i = at(x, y);
      if (sig_[i]) return;
      int h, v, d;
      counts(x, y, h, v, d);
      if (h + v + d == 0) return;
      visited_[i] = p;
      if (decode_bit(zc_context(x, y))) becomes_significant(x, y, p);
    });
  }

  void refinement_pass(int p) {
    scan([&](int x, int y) {
      const std::size_t i = at(x, y);
      if (!sig_[i] || visited_[i] == p) return;
      int h, v, d;
      counts(x, y, h, v, d);
      const int ctx = refined_[i] ? 16 : (h + v + d > 0 ? 15 : 14);  // Table D.4
      if (decode_bit(ctx)) mag_[i] |= std::uint32_t{1} << p;
      known_[i] = p;
      refined_[i] = 1;
    });
  }

  void cleanup_pass(int p) {
    for (int y0 = 0; y0 < h_; y0 += 4)
      for (int x = 0; x < w_; ++x) {
        int y = y0;
        const int y_end = std::min(y0 + 4, h_);
        bool run = y_end - y0 == 4;
        for (int k = y0; run && k < y_end; ++k) {
          const std::size_t i = at(x, k);
          run = !sig_[i] && visited_[i] != p && zc_context(x, k) == 0;
        }
        if (run) {
          if (mq_.decode(cx_[kRunLength]) == 0) continue;
          int r = mq_.decode(cx_[kUniform]) << 1;
          r |= mq_.decode(cx_[kUniform]);
          becomes_significant(x, y0 + r, p);
          y = y0 + r + 1;
        }
        for (; y < y_end; ++y) {
          const std::size_t i = at(x, y);
          if (sig_[i] || visited_[i] == p) continue;
          if (mq_.decode(cx_[zc_context(x, y)])) becomes_significant(x, y, p);
        }
      }
  }

  int w_, h_;
  Band band_;
  int planes_;
  codec::t1::BlockStyle style_;
  std::span<const std::uint8_t> data_;
  std::vector<std::size_t> segment_ends_;
  std::size_t segment_index_ = 0;
  std::size_t segment_begin_ = 0;
  bool segment_open_ = false;
  bool raw_ = false;
  MqDecoder mq_;
  RawReader raw_reader_;
  RefContext cx_[19];
  int next_pass_ = 0;
  int segmentation_errors_ = 0;

  std::vector<std::uint8_t> sig_, neg_, refined_;
  std::vector<std::uint32_t> mag_;
  std::vector<int> known_;    // lowest bit-plane whose bit is known (significant coefficients)
  std::vector<int> visited_;  // plane of the last SPP that coded this coefficient
};

}  // namespace t1ref
