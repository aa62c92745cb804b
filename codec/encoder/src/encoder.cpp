#include "codec/encoder/encoder.h"

#include <algorithm>

#include "codec/codestream/codestream_writer.h"
#include "codec/codestream/jp2.h"
#include "codec/codestream/main_header.h"
#include "codec/encoder/tile_coder.h"
#include "codec/structure/error.h"
#include "codec/tier2/packet_writer.h"
#include "codec/tier2/progression.h"
#include "dwt_cpu/cpu_backend.h"

namespace codec {
namespace {

cs::MainHeader main_header(const SourceImage& image, const EncodeParams& params, const CodingPlan& plan,
                           const std::vector<int>& guard_bits) {
  cs::MainHeader h;
  const ImageGrid& g = plan.grid;
  h.siz.xsiz = static_cast<std::uint64_t>(g.image.x1);
  h.siz.ysiz = static_cast<std::uint64_t>(g.image.y1);
  h.siz.xosiz = static_cast<std::uint64_t>(g.image.x0);
  h.siz.yosiz = static_cast<std::uint64_t>(g.image.y0);
  h.siz.xtsiz = static_cast<std::uint64_t>(g.tile_width);
  h.siz.ytsiz = static_cast<std::uint64_t>(g.tile_height);
  h.siz.xtosiz = static_cast<std::uint64_t>(g.tile_x0);
  h.siz.ytosiz = static_cast<std::uint64_t>(g.tile_y0);
  for (const SourceComponent& c : image.components)
    h.siz.components.push_back(cs::SizComponent{static_cast<unsigned>(c.precision), c.is_signed, 1, 1});

  h.cod.sop = params.sop;
  h.cod.eph = params.eph;
  h.cod.order = static_cast<cs::ProgressionOrder>(static_cast<int>(params.order));
  h.cod.layers = 1;
  h.cod.mct = plan.rct;
  const CodingStyle& style = plan.styles[0];
  h.cod.style.levels = static_cast<unsigned>(style.levels);
  h.cod.style.xcb = static_cast<unsigned>(style.xcb);
  h.cod.style.ycb = static_cast<unsigned>(style.ycb);
  h.cod.style.block_style = params.block_style.to_spcod();
  h.cod.style.transform = cs::WaveletTransform::Reversible5x3;
  if (style.explicit_precincts())
    for (int r = 0; r <= style.levels; ++r) {
      const auto [ppx, ppy] = style.precinct(r);
      h.cod.style.precincts.push_back(cs::PrecinctSize{static_cast<unsigned>(ppx), static_cast<unsigned>(ppy)});
    }

  auto quantization = [&](std::size_t c) {
    cs::Quantization q;
    q.guard_bits = static_cast<unsigned>(guard_bits[c]);
    q.style = cs::QuantizationStyle::None;
    for (int e : plan.quantization[c].exponents) q.steps.push_back(cs::StepSize{static_cast<unsigned>(e), 0});
    return q;
  };
  h.qcd = quantization(0);
  for (std::size_t c = 1; c < image.components.size(); ++c) {
    cs::Quantization q = quantization(c);
    if (q.guard_bits != h.qcd.guard_bits || q.steps.size() != h.qcd.steps.size() ||
        !std::equal(q.steps.begin(), q.steps.end(), h.qcd.steps.begin(),
                    [](const cs::StepSize& a, const cs::StepSize& b) { return a.exponent == b.exponent && a.mantissa == b.mantissa; }))
      h.qccs.push_back(cs::Qcc{static_cast<unsigned>(c), q});
  }
  if (!params.comment.empty()) h.comments.push_back(cs::latin_comment(params.comment));
  return h;
}

t2::Order to_t2(Progression p) { return static_cast<t2::Order>(static_cast<int>(p)); }

// Tier-2: every packet of the tile in progression order, one quality layer holding every pass.
std::vector<std::uint8_t> tile_body(CodedTile& coded, const EncodeParams& params, const std::vector<int>& plan_guard,
                                    const std::vector<int>& final_guard) {
  Tile& tile = coded.tile;
  // Express missing bit-planes against the guard bits the header states.
  for (const TileComponent& tc : tile.components)
    for (const Resolution& res : tc.resolutions)
      for (const Precinct& p : res.precincts)
        for (const PrecinctBand& pb : p.bands)
          for (const CodeBlock& cb : pb.blocks)
            coded.blocks[cb.index].missing_msbs += final_guard[static_cast<std::size_t>(tc.component)] -
                                                   plan_guard[static_cast<std::size_t>(tc.component)];

  std::vector<t2::ComponentGeometry> geometry;
  // One packet writer per precinct, in (component, resolution, precinct) order.
  std::vector<std::vector<std::vector<t2::PrecinctPacketWriter>>> writers(tile.components.size());
  for (const TileComponent& tc : tile.components) {
    t2::ComponentGeometry cg;
    auto& by_resolution = writers[static_cast<std::size_t>(tc.component)];
    for (const Resolution& res : tc.resolutions) {
      cg.resolutions.push_back(t2::ResolutionGeometry{res.rect.x0, res.rect.y0, res.rect.x1, res.rect.y1, res.ppx, res.ppy,
                                                      res.precincts_wide, res.precincts_high});
      auto& list = by_resolution.emplace_back();
      for (const Precinct& p : res.precincts) {
        std::vector<t2::PrecinctBand> bands;
        for (const PrecinctBand& pb : p.bands) {
          t2::PrecinctBand band;
          band.cols = pb.cols;
          band.rows = pb.rows;
          for (const CodeBlock& cb : pb.blocks) {
            const t1::EncodedBlock& eb = coded.blocks[cb.index];
            band.blocks.push_back(t2::CodeBlockCoding{&eb, {static_cast<int>(eb.passes.size())}});
          }
          bands.push_back(std::move(band));
        }
        list.emplace_back(std::move(bands), params.block_style);
      }
    }
    geometry.push_back(std::move(cg));
  }
  std::vector<std::uint8_t> body;
  std::uint16_t sequence = 0;
  for (const t2::PacketId& id :
       t2::progression(to_t2(params.order), 1, tile.rect.x0, tile.rect.y0, tile.rect.x1, tile.rect.y1, geometry))
    writers[static_cast<std::size_t>(id.component)][static_cast<std::size_t>(id.resolution)][static_cast<std::size_t>(id.precinct)]
        .write_packet(id.layer, params.sop, params.eph, sequence++, body);
  return body;
}

}  // namespace

std::vector<std::uint8_t> encode(const SourceImage& image, const EncodeParams& params, FileFormat format) {
  const CodingPlan plan = make_plan(image, params);
  dwt_cpu::CpuBackend dwt(params.threads);
  dwt_cpu::ThreadPool pool(params.threads);

  std::vector<CodedTile> tiles;
  const int count = plan.grid.tile_count();
  tiles.reserve(static_cast<std::size_t>(count));
  std::vector<int> plan_guard, final_guard;
  for (const auto& q : plan.quantization) plan_guard.push_back(q.guard_bits);
  final_guard = plan_guard;
  for (int t = 0; t < count; ++t) {
    tiles.push_back(code_tile(image, plan, params, t, dwt, pool));
    for (std::size_t c = 0; c < final_guard.size(); ++c)
      final_guard[c] = std::max(final_guard[c], tiles.back().guard_bits_needed[c]);
  }

  const cs::MainHeader header = main_header(image, params, plan, final_guard);
  cs::CodestreamWriter writer(header);
  for (CodedTile& tile : tiles) {
    const auto body = tile_body(tile, params, plan_guard, final_guard);
    writer.add_tile_part(static_cast<unsigned>(tile.tile.index), 0, 1, body);
  }
  std::vector<std::uint8_t> codestream = writer.finish();
  if (format == FileFormat::Jp2) return cs::wrap_jp2(codestream, cs::jp2_header_for(header.siz));
  return codestream;
}

}  // namespace codec
