// The Python module gpuj2k: JPEG 2000 encoding of NumPy arrays and image files through the public
// API (gpuj2k/encoder.h). Arrays of shape (H, W) or (H, W, C), uint8, uint16 or int16 (any strides:
// the API reads rows and pixels where they lie); the GIL is released while encoding; every
// gpuj2k::Error becomes gpuj2k.Error (a ValueError) with the library's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

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
                                   std::optional<double> size, int levels, const std::string& format, int threads,
                                   const std::string& dwt, const std::shared_ptr<gpuj2k::Engine>& engine) {
  gpuj2k::EncodeOptions o;
  o.lossless = lossless;
  o.rates_bpp = numbers(rate, "rate");
  o.psnr_db = numbers(psnr, "psnr");
  if (size) o.size_bytes = *size;
  o.levels = levels;
  if (format == "jp2") o.format = gpuj2k::Format::Jp2;
  else if (format != "j2k") throw gpuj2k::Error("format must be \"j2k\" or \"jp2\", got \"" + format + "\"");
  o.threads = threads;
  o.engine = engine;
  if (dwt == "cpu") o.dwt = gpuj2k::DwtDevice::Cpu;
  else if (dwt == "gpu") o.dwt = gpuj2k::DwtDevice::Gpu;
  else if (dwt != "auto") throw gpuj2k::Error("dwt must be \"auto\", \"cpu\" or \"gpu\", got \"" + dwt + "\"");
  return o;
}

py::bytes to_bytes(const std::vector<std::uint8_t>& data) {
  return py::bytes(reinterpret_cast<const char*>(data.data()), data.size());
}

py::bytes encode(const py::array& array, bool lossless, const py::object& rate, const py::object& psnr,
                 std::optional<double> size, int levels, int bits,
                 const std::string& format, int threads, const std::string& dwt,
                 const std::shared_ptr<gpuj2k::Engine>& engine) {
  const gpuj2k::EncodeOptions options = make_options(lossless, rate, psnr, size, levels, format, threads, dwt, engine);
  if (array.ndim() != 2 && array.ndim() != 3)
    throw gpuj2k::Error("the array must have shape (height, width) or (height, width, components), got " +
                        std::to_string(array.ndim()) + " dimensions");
  gpuj2k::ImageView v;
  const py::dtype dtype = array.dtype();
  if (dtype.is(py::dtype::of<std::uint8_t>())) v.type = gpuj2k::SampleType::UInt8;
  else if (dtype.is(py::dtype::of<std::uint16_t>())) v.type = gpuj2k::SampleType::UInt16;
  else if (dtype.is(py::dtype::of<std::int16_t>())) v.type = gpuj2k::SampleType::Int16;
  else throw gpuj2k::Error("the array's dtype must be uint8, uint16 or int16, got " + py::str(py::handle(dtype)).cast<std::string>());
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
  v.size_bytes = v.height == 0 ? 0
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
                      std::optional<double> size, int levels,
                      const std::string& format, int threads, const std::string& dwt,
                 const std::shared_ptr<gpuj2k::Engine>& engine) {
  const gpuj2k::EncodeOptions options = make_options(lossless, rate, psnr, size, levels, format, threads, dwt, engine);
  std::vector<std::uint8_t> out;
  {
    py::gil_scoped_release release;
    out = gpuj2k::encode_file(path, options);
  }
  return to_bytes(out);
}

}  // namespace

PYBIND11_MODULE(gpuj2k, m) {
  m.doc() = "JPEG 2000 encoding (ITU-T T.800 Part 1) with gpuj2k";
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
        py::arg("format") = "j2k", py::arg("threads") = 0, py::arg("dwt") = "auto", py::arg("engine") = py::none(),
        "Encodes a (H, W) or (H, W, C) array of uint8, uint16 or int16 and returns the codestream (or JP2 file) as "
        "bytes. rate: bits per pixel per layer; psnr: dB per layer; size: bytes; bits: significant bits (0: the "
        "dtype's).");
  m.def("encode_file", &encode_file, py::arg("path"), py::kw_only(), py::arg("lossless") = false,
        py::arg("rate") = py::none(), py::arg("psnr") = py::none(), py::arg("size") = py::none(), py::arg("levels") = 5,
        py::arg("format") = "j2k", py::arg("threads") = 0, py::arg("dwt") = "auto", py::arg("engine") = py::none(),
        "Encodes an image file (PNM, PNG, TIFF, ...) and returns the bytes.");
  m.attr("__version__") = gpuj2k::version();
}
