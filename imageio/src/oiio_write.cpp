// Writing through OpenImageIO without changing any sample value. Built into the OpenImageIO
// module (see oiio_module.h), not into the programs themselves.

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <string_view>
#include <vector>

#include "atomic_file.h"
#include "image_checks.h"
#include "oiio_codec.h"
#include "oiio_messages.h"

namespace imageio {
namespace {

OIIO::TypeDesc storage_type(const Image& image) {
  if (image.is_float) return OIIO::TypeDesc::FLOAT;
  if (image.bits_per_sample <= 8) return image.is_signed ? OIIO::TypeDesc::INT8 : OIIO::TypeDesc::UINT8;
  return image.is_signed ? OIIO::TypeDesc::INT16 : OIIO::TypeDesc::UINT16;
}

// Converts to the storage type. Values were checked to be in range
// integers, so the casts are exact.
template <typename T>
std::vector<T> to_storage(const Image& image) {
  std::vector<T> out(image.pixels.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = T(image.pixels[i]);
  return out;
}

std::string describe(const Image& image) {
  return std::to_string(image.bits_per_sample) + "-bit " + (image.is_signed ? "signed" : "unsigned") +
         " integer samples";
}

void write_pixels(OIIO::ImageOutput& out, const std::string& path, const Image& image, OIIO::TypeDesc type) {
  bool ok = false;
  switch (type.basetype) {
    case OIIO::TypeDesc::UINT8:
      ok = out.write_image(type, to_storage<std::uint8_t>(image).data());
      break;
    case OIIO::TypeDesc::INT8:
      ok = out.write_image(type, to_storage<std::int8_t>(image).data());
      break;
    case OIIO::TypeDesc::UINT16:
      ok = out.write_image(type, to_storage<std::uint16_t>(image).data());
      break;
    case OIIO::TypeDesc::INT16:
      ok = out.write_image(type, to_storage<std::int16_t>(image).data());
      break;
    default:
      ok = out.write_image(type, image.pixels.data());
  }
  if (!ok) throw IoError(path, detail::oiio_message(out.geterror(), "cannot write pixel data"));
}

}  // namespace

namespace detail {

void write_with_oiio(const std::string& path, const Image& image) {
  const OIIO::TypeDesc type = storage_type(image);
  // The writer is chosen from the real path: the temporary's name is not
  // what decides the format.
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw IoError(path, detail::oiio_message(OIIO::geterror(), "unknown image format"));

  OIIO::ImageSpec spec(image.width, image.height, image.channels, type);
  // Stops writers from un-premultiplying colour by alpha (PNG, TIFF).
  spec.attribute("oiio:UnassociatedAlpha", 1);
  // Some writers (PNM in newer OpenImageIO) pick their bit depth from this.
  if (!image.is_float) spec.attribute("oiio:BitsPerSample", int(type.size() * 8));
  if (image.x_pixels_per_metre > 0 && image.y_pixels_per_metre > 0) {
    // Per centimetre: a unit TIFF, PNG (pHYs, per metre) and JPEG (JFIF) writers all convert from.
    spec.attribute("XResolution", static_cast<float>(image.x_pixels_per_metre / 100));
    spec.attribute("YResolution", static_cast<float>(image.y_pixels_per_metre / 100));
    spec.attribute("ResolutionUnit", "cm");
    // The pixel's width over its height, for OpenImageIO's TIFF writer alone: it derives
    // YResolution from it (XResolution times it) and would write square pixels without it, while
    // its JPEG writer divides by it instead (OpenImageIO 2.4) and reads YResolution right.
    if (std::string_view(out->format_name()) == "tiff")
      spec.attribute("PixelAspectRatio", static_cast<float>(image.y_pixels_per_metre / image.x_pixels_per_metre));
  }
  if (!image.icc_profile.empty())
    spec.attribute("ICCProfile", OIIO::TypeDesc(OIIO::TypeDesc::UINT8, static_cast<int>(image.icc_profile.size())),
                   image.icc_profile.data());

  detail::write_atomically(path, [&](const std::string& temporary) {
    if (!out->open(temporary, spec)) {
      throw IoError(path, detail::oiio_message(out->geterror(), "cannot open for writing"));
    }
    // Writers silently switch to the nearest type they support (PNG
    // turns int16 into uint8, EXR turns integers into half, OIIO 2.4's
    // PNM always uses uint8); OIIO would then rescale the values, so for
    // integer images that is an error.
    if (!image.is_float && out->spec().format != type) {
      // Finish the doomed temporary anyway: some writers (libpng)
      // complain on stderr when closed without pixels.
      try {
        write_pixels(*out, path, image, type);
      } catch (const IoError&) {
      }
      out->close();
      throw IoError(path,
                    std::string("the ") + out->format_name() + " format cannot store " + describe(image) + " exactly");
    }
    write_pixels(*out, path, image, type);
    if (!out->close()) {
      throw IoError(path, detail::oiio_message(out->geterror(), "cannot finish writing"));
    }
  });
}

}  // namespace detail
}  // namespace imageio
