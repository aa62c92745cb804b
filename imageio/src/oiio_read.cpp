// Reading through OpenImageIO, keeping each file's native sample type. Built into the OpenImageIO
// module (see oiio_module.h), not into the programs themselves.

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <string_view>
#include <vector>

#include "image_checks.h"
#include "imageio/pnm.h"
#include "oiio_codec.h"
#include "oiio_messages.h"

namespace imageio {
namespace {

// Some readers (PNM) fail on truncated data without saying why.
constexpr const char* kReadFailed = "cannot read pixel data (truncated or corrupt file?)";

// How a file's samples map onto an Image, and the type we ask OIIO for.
struct SampleKind {
  OIIO::TypeDesc read_as;
  int bits = 0;
  bool is_signed = false;
  bool is_float = false;
};

bool kind_of(OIIO::TypeDesc type, SampleKind& kind) {
  switch (type.basetype) {
    case OIIO::TypeDesc::UINT8:
      kind = {OIIO::TypeDesc::UINT8, 8, false, false};
      return true;
    case OIIO::TypeDesc::INT8:
      kind = {OIIO::TypeDesc::INT8, 8, true, false};
      return true;
    case OIIO::TypeDesc::UINT16:
      kind = {OIIO::TypeDesc::UINT16, 16, false, false};
      return true;
    case OIIO::TypeDesc::INT16:
      kind = {OIIO::TypeDesc::INT16, 16, true, false};
      return true;
    case OIIO::TypeDesc::HALF:
    case OIIO::TypeDesc::FLOAT:
      kind = {OIIO::TypeDesc::FLOAT, 32, false, true};
      return true;
    default:
      return false;
  }
}

// Files may declare a type per channel. Reading converts every channel to one
// type, which OIIO does by rescaling integers; that would change values, so
// integer channels must all share the file's type. Mixing half and float is
// fine because both are read as float without rescaling.
SampleKind sample_kind(const std::string& path, const OIIO::ImageSpec& spec) {
  SampleKind kind;
  if (!kind_of(spec.format, kind)) {
    throw IoError(path, std::string("unsupported sample type ") + spec.format.c_str());
  }
  for (const OIIO::TypeDesc& channel_type : spec.channelformats) {
    SampleKind channel_kind;
    if (!kind_of(channel_type, channel_kind)) {
      throw IoError(path, std::string("unsupported sample type ") + channel_type.c_str());
    }
    if (channel_kind.read_as != kind.read_as) {
      throw IoError(path, "unsupported mix of per-channel sample types");
    }
  }
  return kind;
}

void read_pixels(OIIO::ImageInput& in, const std::string& path, int channels, OIIO::TypeDesc type, void* data) {
  const bool ok = in.read_image(0, 0, 0, channels, type, data);
  // OIIO 2.4's TIFF reader zero-fills truncated strips and still returns
  // true; only a pending error message tells, so that counts as failure.
  const std::string message = in.geterror();
  if (!ok || !message.empty()) throw IoError(path, detail::oiio_message(message, kReadFailed));
}

template <typename T>
void read_integers(OIIO::ImageInput& in, const std::string& path, OIIO::TypeDesc type, Image& image) {
  std::vector<T> buffer(image.pixels.size());
  read_pixels(in, path, image.channels, type, buffer.data());
  for (std::size_t i = 0; i < buffer.size(); ++i) image.pixels[i] = float(buffer[i]);
}

// The file's resolution in pixels per metre, from OpenImageIO's XResolution, YResolution and
// ResolutionUnit (readers report inches, centimetres or metres); a file that gives no unit gives
// only an aspect ratio, which is not kept.
void read_resolution(const OIIO::ImageSpec& spec, Image& image) {
  const float x = spec.get_float_attribute("XResolution"), y = spec.get_float_attribute("YResolution");
  if (!(x > 0) || !(y > 0)) return;
  const std::string unit = spec.get_string_attribute("ResolutionUnit");
  double per_unit_to_per_metre = 0;
  if (unit == "in" || unit == "inch")
    per_unit_to_per_metre = 100 / 2.54;
  else if (unit == "cm")
    per_unit_to_per_metre = 100;
  else if (unit == "mm")
    per_unit_to_per_metre = 1000;
  else if (unit == "m")
    per_unit_to_per_metre = 1;
  if (per_unit_to_per_metre == 0) return;
  image.x_pixels_per_metre = x * per_unit_to_per_metre;
  image.y_pixels_per_metre = y * per_unit_to_per_metre;
}

}  // namespace

namespace detail {

Image read_with_oiio(const std::string& path) {
  // Without this hint OIIO premultiplies colour by alpha while reading
  // files that store unassociated alpha (PNG, TIFF), which changes values.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw IoError(path, detail::oiio_message(OIIO::geterror(), "cannot open image"));

  const OIIO::ImageSpec& spec = in->spec();
  if (spec.depth > 1) throw IoError(path, "volume images are not supported");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw IoError(path, "image has no pixels");
  }
  const std::uint64_t samples = std::uint64_t(spec.width) * std::uint64_t(spec.height) * std::uint64_t(spec.nchannels);
  if (samples > detail::kMaxSamples) {
    throw IoError(path, "image too large: " + std::to_string(samples) + " samples exceeds the limit of " +
                            std::to_string(detail::kMaxSamples));
  }
  const SampleKind kind = sample_kind(path, spec);
  // A Netpbm file under another extension. OpenImageIO 2.4 rescales 16-bit
  // PGM/PPM samples through float and gets the top of the range wrong (65535
  // reads back as 65534), so our own reader takes over; it does for 8-bit
  // files as well, so that a PNM reads the same whatever its name. (OIIO's
  // "pnm" also covers PFM, which it reports as float: that stays here.)
  if (std::string_view(in->format_name()) == "pnm" && !kind.is_float) {
    in->close();
    return read_pnm(path);
  }

  Image image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.bits_per_sample = kind.bits;
  image.is_signed = kind.is_signed;
  image.is_float = kind.is_float;
  image.pixels.resize(samples);
  if (const OIIO::ParamValue* icc = spec.find_attribute("ICCProfile");
      icc != nullptr && icc->type().basetype == OIIO::TypeDesc::UINT8) {
    const auto* bytes = static_cast<const std::uint8_t*>(icc->data());
    image.icc_profile.assign(bytes, bytes + icc->type().numelements() * icc->nvalues());
  }

  read_resolution(spec, image);

  switch (kind.read_as.basetype) {
    case OIIO::TypeDesc::UINT8:
      read_integers<std::uint8_t>(*in, path, kind.read_as, image);
      break;
    case OIIO::TypeDesc::INT8:
      read_integers<std::int8_t>(*in, path, kind.read_as, image);
      break;
    case OIIO::TypeDesc::UINT16:
      read_integers<std::uint16_t>(*in, path, kind.read_as, image);
      break;
    case OIIO::TypeDesc::INT16:
      read_integers<std::int16_t>(*in, path, kind.read_as, image);
      break;
    default:
      read_pixels(*in, path, image.channels, kind.read_as, image.pixels.data());
  }
  if (!in->close()) {
    throw IoError(path, detail::oiio_message(in->geterror(), "cannot close image"));
  }
  return image;
}

}  // namespace detail
}  // namespace imageio
