// The Python module gpuj2k: JPEG 2000 encoding (EBCOT or HTJ2K code-blocks) of NumPy arrays and
// image files through the public API (gpuj2k/encoder.h), and decoding. Arrays of shape (H, W) or
// (H, W, C), uint8, uint16 or int16 (any strides: the API reads rows and pixels where they lie);
// the GIL is released while coding; every gpuj2k::Error becomes gpuj2k.Error (a ValueError) with
// the library's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gpuj2k/decoder.h"
#include "gpuj2k/encoder.h"

namespace py = pybind11;

namespace {

// A number or a sequence of numbers (one per quality layer); None: none.
std::vector<double> numbers(const py::object& value, const char* name) {
  if (value.is_none()) return {};
  try {
    if (py::isinstance<py::sequence>(value)) return value.cast<std::vector<double>>();
    return {value.cast<double>()};
  } catch (const py::cast_error&) {
    throw gpuj2k::Error(std::string(name) + " must be a number or a sequence of numbers");
  }
}

// The options common to both entry points, from Python's keyword arguments.
gpuj2k::EncodeOptions make_options(bool lossless, const py::object& rate, const py::object& psnr,
                                   std::optional<double> size, int levels, const std::string& format, bool ht,
                                   int threads, const std::string& dwt, const std::shared_ptr<gpuj2k::Engine>& engine) {
  gpuj2k::EncodeOptions o;
  o.lossless = lossless;
  o.ht = ht;
  o.rates_bpp = numbers(rate, "rate");
  o.psnr_db = numbers(psnr, "psnr");
  if (size) o.size_bytes = *size;
  o.levels = levels;
  if (format == "jp2")
    o.format = gpuj2k::Format::Jp2;
  else if (format == "jph")
    o.format = gpuj2k::Format::Jph;
  else if (format != "j2k")
    throw gpuj2k::Error("format must be \"j2k\", \"jp2\" or \"jph\", got \"" + format + "\"");
  o.threads = threads;
  o.engine = engine;
  if (dwt == "cpu")
    o.dwt = gpuj2k::DwtDevice::Cpu;
  else if (dwt == "gpu")
    o.dwt = gpuj2k::DwtDevice::Gpu;
  else if (dwt != "auto")
    throw gpuj2k::Error("dwt must be \"auto\", \"cpu\" or \"gpu\", got \"" + dwt + "\"");
  return o;
}

py::bytes to_bytes(const std::vector<std::uint8_t>& data) {
  return py::bytes(reinterpret_cast<const char*>(data.data()), data.size());
}

py::bytes encode(const py::array& array, bool lossless, const py::object& rate, const py::object& psnr,
                 std::optional<double> size, int levels, int bits, const std::string& format, bool ht, int threads,
                 const std::string& dwt, const std::shared_ptr<gpuj2k::Engine>& engine) {
  const gpuj2k::EncodeOptions options =
      make_options(lossless, rate, psnr, size, levels, format, ht, threads, dwt, engine);
  if (array.ndim() != 2 && array.ndim() != 3)
    throw gpuj2k::Error("the array must have shape (height, width) or (height, width, components), got " +
                        std::to_string(array.ndim()) + " dimensions");
  gpuj2k::ImageView v;
  const py::dtype dtype = array.dtype();
  if (dtype.is(py::dtype::of<std::uint8_t>()))
    v.type = gpuj2k::SampleType::UInt8;
  else if (dtype.is(py::dtype::of<std::uint16_t>()))
    v.type = gpuj2k::SampleType::UInt16;
  else if (dtype.is(py::dtype::of<std::int16_t>()))
    v.type = gpuj2k::SampleType::Int16;
  else
    throw gpuj2k::Error("the array's dtype must be uint8, uint16 or int16, got " +
                        py::str(py::handle(dtype)).cast<std::string>());
  const py::ssize_t item = array.itemsize();
  const py::ssize_t components = array.ndim() == 3 ? array.shape(2) : 1;
  // The API takes interleaved pixels in rows: components must be adjacent and pixels evenly spaced
  // by whole pixels; anything else (transposed or sliced arrays) is copied into that layout first.
  py::array contiguous = array;
  const bool fits = (array.ndim() == 2 || array.strides(2) == item) && array.strides(1) == item * components &&
                    array.strides(0) >= array.strides(1) * array.shape(1);
  if (!fits) contiguous = py::array::ensure(array, py::array::c_style | py::array::forcecast);
  v.data = contiguous.data();
  v.height = static_cast<int>(contiguous.shape(0));
  v.width = static_cast<int>(contiguous.shape(1));
  v.components = static_cast<int>(components);
  v.bits = bits;
  v.row_stride = static_cast<std::size_t>(contiguous.strides(0));
  v.size_bytes = v.height == 0
                     ? 0
                     : static_cast<std::size_t>(contiguous.strides(0)) * static_cast<std::size_t>(v.height - 1) +
                           static_cast<std::size_t>(item * components * contiguous.shape(1));
  std::vector<std::uint8_t> out;
  {
    py::gil_scoped_release release;
    out = gpuj2k::encode(v, options);
  }
  return to_bytes(out);
}

py::bytes encode_file(const std::string& path, bool lossless, const py::object& rate, const py::object& psnr,
                      std::optional<double> size, int levels, const std::string& format, bool ht, int threads,
                      const std::string& dwt, const std::shared_ptr<gpuj2k::Engine>& engine) {
  const gpuj2k::EncodeOptions options =
      make_options(lossless, rate, psnr, size, levels, format, ht, threads, dwt, engine);
  std::vector<std::uint8_t> out;
  {
    py::gil_scoped_release release;
    out = gpuj2k::encode_file(path, options);
  }
  return to_bytes(out);
}

gpuj2k::DecodeOptions decode_options(int reduce, int layers, const std::optional<std::vector<int>>& components,
                                     const std::optional<std::vector<std::int64_t>>& region, int threads,
                                     const std::string& dwt) {
  gpuj2k::DecodeOptions o;
  o.reduce = reduce;
  o.layers = layers;
  if (components) o.components = *components;
  if (region) {
    if (region->size() != 4) throw gpuj2k::Error("region must be (x, y, width, height)");
    o.region = gpuj2k::Region{(*region)[0], (*region)[1], (*region)[2], (*region)[3]};
  }
  o.threads = threads;
  if (dwt == "gpu")
    o.dwt = gpuj2k::DwtDevice::Gpu;
  else if (dwt != "cpu" && dwt != "auto")
    throw gpuj2k::Error("dwt must be \"auto\", \"cpu\" or \"gpu\", got \"" + dwt + "\"");
  return o;
}

// A decoded image as one array: (H, W) for one component, (H, W, C) for several, all of one size;
// uint8 up to 8 unsigned bits, uint16 up to 16, int16 for signed up to 16, int32 up to 31, int64
// beyond (JPEG 2000 allows 38).
py::array to_array(gpuj2k::DecodedImage&& image) {
  if (image.components.empty()) throw gpuj2k::Error("the image has no components");
  const gpuj2k::DecodedComponent& first = image.components.front();
  bool any_signed = false, all_unsigned_8 = true, all_unsigned_16 = true, all_signed_16 = true;
  int deepest = 0;
  for (std::size_t c = 0; c < image.components.size(); ++c) {
    const gpuj2k::DecodedComponent& comp = image.components[c];
    if (comp.width != first.width || comp.height != first.height)
      throw gpuj2k::Error("component " + std::to_string(c) + " is " + std::to_string(comp.width) + "x" +
                          std::to_string(comp.height) + ", component 0 " + std::to_string(first.width) + "x" +
                          std::to_string(first.height) + " (subsampled): decode them one by one with components=[i]");
    any_signed |= comp.is_signed;
    all_unsigned_8 &= !comp.is_signed && comp.precision <= 8;
    all_unsigned_16 &= !comp.is_signed && comp.precision <= 16;
    all_signed_16 &= comp.is_signed ? comp.precision <= 16 : comp.precision <= 15;
    deepest = std::max(deepest, comp.precision);
  }
  const auto h = static_cast<py::ssize_t>(first.height), w = static_cast<py::ssize_t>(first.width);
  const auto nc = static_cast<py::ssize_t>(image.components.size());
  std::vector<py::ssize_t> shape = nc == 1 ? std::vector<py::ssize_t>{h, w} : std::vector<py::ssize_t>{h, w, nc};
  auto fill = [&](auto tag) {
    using T = decltype(tag);
    py::array_t<T> out(shape);
    T* dst = out.mutable_data();
    for (py::ssize_t c = 0; c < nc; ++c) {
      const gpuj2k::DecodedComponent& comp = image.components[static_cast<std::size_t>(c)];
      auto copy = [&](const auto& s) {
        for (std::size_t i = 0; i < s.size(); ++i) dst[static_cast<py::ssize_t>(i) * nc + c] = static_cast<T>(s[i]);
      };
      comp.precision > 31 ? copy(comp.wide_samples) : copy(comp.samples);
    }
    return py::array(out);
  };
  if (all_unsigned_8) return fill(std::uint8_t{});
  if (all_unsigned_16) return fill(std::uint16_t{});
  if (any_signed && all_signed_16) return fill(std::int16_t{});
  if (deepest > 31) return fill(std::int64_t{});
  return fill(std::int32_t{});
}

py::array decode(const py::bytes& data, int reduce, int layers, const std::optional<std::vector<int>>& components,
                 const std::optional<std::vector<std::int64_t>>& region, int threads, const std::string& dwt) {
  const gpuj2k::DecodeOptions options = decode_options(reduce, layers, components, region, threads, dwt);
  const std::string_view bytes = data;
  gpuj2k::DecodedImage image;
  {
    py::gil_scoped_release release;
    image = gpuj2k::decode(bytes.data(), bytes.size(), options);
  }
  return to_array(std::move(image));
}

py::array decode_file(const std::string& path, int reduce, int layers,
                      const std::optional<std::vector<int>>& components,
                      const std::optional<std::vector<std::int64_t>>& region, int threads, const std::string& dwt) {
  const gpuj2k::DecodeOptions options = decode_options(reduce, layers, components, region, threads, dwt);
  gpuj2k::DecodedImage image;
  {
    py::gil_scoped_release release;
    image = gpuj2k::decode_file(path, options);
  }
  return to_array(std::move(image));
}

}  // namespace

PYBIND11_MODULE(gpuj2k, m) {
  m.doc() = "JPEG 2000 encoding and decoding (ITU-T T.800 Part 1, T.814 HTJ2K) with gpuj2k";
  static py::exception<gpuj2k::Error> error(m, "Error", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gpuj2k::Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
  py::class_<gpuj2k::Engine, std::shared_ptr<gpuj2k::Engine>>(
      m, "Engine",
      "Worker threads (and a GL context when the DWT runs on the GPU) that encodes given engine=... share, "
      "from any Python thread.")
      .def(py::init<int>(), py::arg("threads") = 0)
      .def_property_readonly("threads", &gpuj2k::Engine::threads);
  m.def("encode", &encode, py::arg("array"), py::kw_only(), py::arg("lossless") = false, py::arg("rate") = py::none(),
        py::arg("psnr") = py::none(), py::arg("size") = py::none(), py::arg("levels") = 5, py::arg("bits") = 0,
        py::arg("format") = "j2k", py::arg("ht") = false, py::arg("threads") = 0, py::arg("dwt") = "auto",
        py::arg("engine") = py::none(),
        "Encodes a (H, W) or (H, W, C) array of uint8, uint16 or int16 and returns the codestream (or JP2 or JPH "
        "file) as bytes. rate: bits per pixel per layer; psnr: dB per layer; size: bytes; bits: significant bits "
        "(0: the dtype's); format: \"j2k\", \"jp2\" or \"jph\" (HT only); ht: HTJ2K (Part 15) code-blocks, one "
        "quality layer.");
  m.def("encode_file", &encode_file, py::arg("path"), py::kw_only(), py::arg("lossless") = false,
        py::arg("rate") = py::none(), py::arg("psnr") = py::none(), py::arg("size") = py::none(), py::arg("levels") = 5,
        py::arg("format") = "j2k", py::arg("ht") = false, py::arg("threads") = 0, py::arg("dwt") = "auto",
        py::arg("engine") = py::none(),
        "Encodes an image file (PNM, PNG, TIFF, ...) and returns the bytes; as encode.");
  m.def("decode", &decode, py::arg("data"), py::kw_only(), py::arg("reduce") = 0, py::arg("layers") = 0,
        py::arg("components") = py::none(), py::arg("region") = py::none(), py::arg("threads") = 0,
        py::arg("dwt") = "cpu",
        "Decodes a codestream, JP2 or JPH file given as bytes into a (H, W) or (H, W, C) array (uint8, uint16, int16, "
        "int32 or int64 by the samples' precision). reduce: finest levels dropped; layers: 0 for all; components: "
        "indices "
        "in output order; region: (x, y, width, height) on the full-resolution grid.");
  m.def("decode_file", &decode_file, py::arg("path"), py::kw_only(), py::arg("reduce") = 0, py::arg("layers") = 0,
        py::arg("components") = py::none(), py::arg("region") = py::none(), py::arg("threads") = 0,
        py::arg("dwt") = "cpu", "Decodes a file (.j2k, .j2c, .jp2, .jph); as decode.");
  m.attr("__version__") = gpuj2k::version();
}
