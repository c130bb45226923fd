// The Python module `vsil`: volumes as numpy arrays, renders in one process with the options of
// `vsil render` by the same names, and the postfx stages on any arrays.
//
//   import vsil
//   volume = vsil.load("bonsai.vti")                 # or vsil.Volume(ndarray), vsil.generate(...)
//   renderer = vsil.Renderer()                       # one GL context, reused by every render
//   frame = renderer.render(volume, iso=40, width_near=4, width_far=1)
//   frame.image, frame.state, frame.depth, frame.metadata
//
// Keyword arguments become the command line's flags (width_near=4 -> --width-near 4) and are
// parsed by the CLI's own table (cli/cli_render_options.h), so the two cannot drift apart.
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <opencv2/imgproc.hpp>

#include "cli/cli_gl_options.h"
#include "cli/cli_render_options.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/volume.h"
#include "io/sample_sink.h"
#include "io/volume_loader.h"
#include "job/render_job.h"
#include "postfx/broaden.h"
#include "postfx/line_width.h"

namespace py = pybind11;

namespace vsil::python {
namespace {

// ---- volumes ----

py::dtype dtypeOf(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return py::dtype::of<std::uint8_t>();
    case SampleType::Int8:
      return py::dtype::of<std::int8_t>();
    case SampleType::UInt16:
      return py::dtype::of<std::uint16_t>();
    case SampleType::Int16:
      return py::dtype::of<std::int16_t>();
    case SampleType::Float32:
      break;
  }
  return py::dtype::of<float>();
}

// A Python volume: the Volume (shared, so renders and numpy views can keep it alive) and, when it
// wraps a numpy array, that array.
struct PyVolume {
  std::shared_ptr<Volume> volume;
  py::object array = py::none();
};

template <typename C>
bool borrowIfType(Volume& volume, const py::array& array, std::shared_ptr<void> keepAlive) {
  if (!py::isinstance<py::array_t<C>>(array) || !array.dtype().is(py::dtype::of<C>())) {
    return false;
  }
  // vsil never writes a volume's samples once it is made, so read-only arrays (memory maps,
  // frombuffer) are wrapped too.
  volume.borrow(static_cast<C*>(const_cast<void*>(array.data())), std::move(keepAlive));
  return true;
}

// As every reader: a NaN or infinite sample is bad input, not a value to render. Checked when
// an array is wrapped and again at each upload (its samples may have changed in place).
void requireFiniteSamples(const Volume& volume) {
  volume.visit([](auto samples) {
    if constexpr (std::is_floating_point_v<typename decltype(samples)::value_type>) {
      for (std::size_t i = 0; i < samples.size(); ++i) {
        if (!std::isfinite(samples[i])) io::checkFinite("vsil.Volume", i, samples[i]);
      }
    }
  });
}

PyVolume wrapArray(const py::array& array, std::vector<double> spacing, std::string name) {
  if (array.ndim() != 3) {
    throw InputError("vsil.Volume: expected a 3-dimensional array (z, y, x), got " +
                     std::to_string(array.ndim()) + " dimensions");
  }
  if (!(array.flags() & py::array::c_style)) {
    throw InputError(
        "vsil.Volume: the array is not C-contiguous; pass numpy.ascontiguousarray(a) (a copy)");
  }
  if (spacing.size() != 3 || !(spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0)) {
    throw InputError("vsil.Volume: spacing must be three positive numbers (x, y, z)");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (array.shape(axis) < 1 || array.shape(axis) > limits::kMaxVolumeSide) {
      throw InputError("vsil.Volume: each axis must have 1 .. " +
                       std::to_string(limits::kMaxVolumeSide) + " samples, not " +
                       std::to_string(array.shape(axis)));
    }
  }
  auto volume = std::make_shared<Volume>();
  volume->name = name;
  volume->source = "<numpy array>";
  volume->dims = {int(array.shape(2)), int(array.shape(1)), int(array.shape(0))};
  volume->spacing = {spacing[0], spacing[1], spacing[2]};
  // The array stays referenced while any volume borrows it; the last release takes the GIL.
  std::shared_ptr<void> keepAlive(new py::object(array), [](void* held) {
    py::gil_scoped_acquire gil;
    delete static_cast<py::object*>(held);
  });
  if (!borrowIfType<std::uint8_t>(*volume, array, keepAlive) &&
      !borrowIfType<std::int8_t>(*volume, array, keepAlive) &&
      !borrowIfType<std::uint16_t>(*volume, array, keepAlive) &&
      !borrowIfType<std::int16_t>(*volume, array, keepAlive) &&
      !borrowIfType<float>(*volume, array, keepAlive)) {
    throw InputError("vsil.Volume: samples of dtype " + std::string(py::str(array.dtype())) +
                     " are not supported (uint8, int8, uint16, int16, float32; convert with "
                     "a.astype(numpy.float32))");
  }
  requireFiniteSamples(*volume);
  return {volume, array};
}

// The samples as a numpy array (z, y, x) on the volume's memory, keeping `self` alive.
py::array dataOf(const py::object& self) {
  const PyVolume& v = self.cast<const PyVolume&>();
  if (!v.array.is_none()) return v.array;
  const Volume& volume = *v.volume;
  const std::size_t size = sampleTypeSize(volume.type());
  const std::vector<py::ssize_t> shape{volume.dims.z, volume.dims.y, volume.dims.x};
  const std::vector<py::ssize_t> strides{py::ssize_t(size) * volume.dims.x * volume.dims.y,
                                         py::ssize_t(size) * volume.dims.x, py::ssize_t(size)};
  const void* data = volume.visit([](auto samples) -> const void* { return samples.data(); });
  return py::array(dtypeOf(volume.type()), shape, strides, data, self);
}

// ---- keyword arguments as flags ----

// One flag and its value as the command line writes it: width_near=4 -> "--width-near", "4";
// True -> the bare flag; False and None -> nothing; size=(640, 480) -> "640x480"; other
// sequences -> "a,b,c".
void appendFlag(std::vector<std::string>& args, const std::string& key, const py::handle& value) {
  std::string flag = "--" + key;
  for (char& c : flag) c = c == '_' ? '-' : c;
  if (value.is_none()) return;
  if (py::isinstance<py::bool_>(value)) {
    if (value.cast<bool>()) args.push_back(flag);
    return;
  }
  args.push_back(flag);
  if (py::isinstance<py::str>(value)) {
    args.push_back(value.cast<std::string>());
  } else if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    std::string joined;
    for (const py::handle item : value) {
      joined += (joined.empty() ? "" : key == "size" ? "x" : ",") + std::string(py::str(item));
    }
    args.push_back(joined);
  } else {
    args.push_back(py::str(value));  // numbers: Python's shortest round-trip text
  }
}

// Parses `kwargs` with `app`'s options; a keyword with no flag of that name is a ValueError
// naming it.
void parseKeywords(CLI::App& app, const py::kwargs& kwargs, const std::string& function) {
  std::vector<std::string> args;
  for (const auto& [key, value] : kwargs) {
    const std::string name = key.cast<std::string>();
    std::string flag = "--" + name;
    for (char& c : flag) c = c == '_' ? '-' : c;
    const CLI::Option* option = app.get_option_no_throw(flag);
    if (name.empty() || name == "help" || !option) {
      throw InputError(function + ": unknown keyword '" + name + "'");
    }
    // A switch (ortho=...) takes True or False: "no", 0, "" or [] would otherwise turn it on.
    if (option->get_expected_max() == 0 && !value.is_none() && !py::isinstance<py::bool_>(value)) {
      throw InputError(function + ": " + name + " must be True or False (got " +
                       std::string(py::repr(value)).substr(0, 40) + ")");
    }
    appendFlag(args, name, value);
  }
  std::reverse(args.begin(), args.end());  // CLI11 parses a vector from its back
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw InputError(function + ": " + e.what());
  }
}

// The keywords every volume-loading call takes: the volume flags of the CLI (dims, type,
// spacing, endian, crop, stride, series, max_memory).
LoadOptions loadOptionsFromKeywords(const py::kwargs& kwargs, const std::string& function) {
  CLI::App app;
  cli::VolumeOptions options;
  cli::addVolumeOptions(app, options);
  parseKeywords(app, kwargs, function);
  return cli::toLoadOptions(options);
}

PyVolume load(const std::string& spec, const py::kwargs& kwargs) {
  const LoadOptions options = loadOptionsFromKeywords(kwargs, "vsil.load");
  Volume loaded;
  {
    py::gil_scoped_release release;
    loaded = loadVolume(spec, options);
  }
  for (const std::string& warning : loaded.warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, warning.c_str(), 1) != 0) throw py::error_already_set();
  }
  return {std::make_shared<Volume>(std::move(loaded))};
}

// ---- rendering ----

struct Frame {
  py::array image;  // H x W x 4 uint8, RGBA
  py::array state;  // H x W uint8, PixelState (0 empty, 1 filled, 2 contour, 3 silhouette)
  py::array depth;  // H x W float32, normalized depth, NaN where none
  py::object metadata;
  std::vector<std::string> warnings;
};

template <typename T>
py::array arrayFromMat(const cv::Mat& mat, int channels) {
  std::vector<py::ssize_t> shape{mat.rows, mat.cols};
  if (channels > 1) shape.push_back(channels);
  py::array_t<T> array(shape);
  const cv::Mat contiguous = mat.isContinuous() ? mat : mat.clone();
  std::memcpy(array.mutable_data(), contiguous.data, contiguous.total() * contiguous.elemSize());
  return array;
}

py::object jsonToPython(const nlohmann::json& json) {
  return py::module_::import("json").attr("loads")(json.dump());
}

class PythonRenderer {
 public:
  explicit PythonRenderer(const py::kwargs& kwargs) {
    CLI::App app;
    cli::GlOptions options;
    cli::addGlOptions(app, options);
    parseKeywords(app, kwargs, "vsil.Renderer");
    const gl::ContextOptions context = cli::toContextOptions(options);
    job_ = std::make_unique<RenderJob>(context);
  }

  // Uploads `volume` now (render does it when the volume changes; call this after changing a
  // volume's samples in place), in bricks of the last render's max_texture_mib.
  void upload(const PyVolume& volume) { uploadInBricks(volume, uploadedTextureBytes_); }

  Frame render(const py::object& input, const py::kwargs& kwargs) {
    // Flags that choose what render does not own here: the context is the Renderer's, and a
    // Volume is read already.
    const bool isPath = py::isinstance<py::str>(input);
    for (const char* key : {"gl", "gl_device"}) {
      if (kwargs.contains(key)) {
        throw InputError("vsil.Renderer.render: " + std::string(key) +
                         " is chosen when the Renderer is made: vsil.Renderer(" + key + "=...)");
      }
    }
    for (const char* key : {"dims", "type", "spacing", "endian", "crop", "stride", "series"}) {
      if (!isPath && kwargs.contains(key)) {
        throw InputError("vsil.Renderer.render: " + std::string(key) +
                         " applies when a file is read: vsil.load(path, " + key + "=...)");
      }
    }
    CLI::App app;
    cli::RenderFlags flags;
    cli::addRenderOptions(app, flags);
    parseKeywords(app, kwargs, "vsil.Renderer.render");
    const RenderRequest request = cli::toRenderRequest(flags);
    const LoadOptions loadOptions = cli::toLoadOptions(flags.volume);
    RenderJob::checkRequest(request, loadOptions.limits);

    if (isPath) {
      // Read on every call (the file may have changed); a sweep loads once with vsil.load.
      const std::string spec = input.cast<std::string>();
      py::gil_scoped_release release;
      job_->load(spec, RenderJob::loadOptionsFor(request, loadOptions));
      uploaded_.reset();
    } else {
      const PyVolume& volume = input.cast<const PyVolume&>();
      const std::uint64_t textureBytes = loadOptions.limits.maxTextureBytes;
      if (volume.volume != uploaded_ || textureBytes != uploadedTextureBytes_) {
        uploadInBricks(volume, textureBytes);
      }
    }

    RenderOutput output;
    {
      py::gil_scoped_release release;
      output = job_->render(request, loadOptions.limits);
    }
    cv::Mat rgba;
    cv::cvtColor(output.image, rgba,
                 output.image.channels() == 4 ? cv::COLOR_BGRA2RGBA : cv::COLOR_BGR2RGBA);
    Frame frame;
    frame.image = arrayFromMat<std::uint8_t>(rgba, 4);
    frame.state = arrayFromMat<std::uint8_t>(output.result.frame.state, 1);
    frame.depth = arrayFromMat<float>(output.result.frame.depth, 1);
    frame.metadata = jsonToPython(output.metadata);
    frame.warnings = output.warnings;
    const py::object warn = py::module_::import("warnings").attr("warn");
    for (const std::string& warning : output.warnings) warn("vsil: " + warning);
    return frame;
  }

 private:
  void uploadInBricks(const PyVolume& volume, std::uint64_t maxTextureBytes) {
    requireFiniteSamples(*volume.volume);
    py::gil_scoped_release release;
    job_->setVolume(Volume::sharing(volume.volume), volume.volume->source, maxTextureBytes);
    uploaded_ = volume.volume;
    uploadedTextureBytes_ = maxTextureBytes;
  }

  std::unique_ptr<RenderJob> job_;
  std::shared_ptr<Volume> uploaded_;  // the volume the texture holds, when given as a Volume
  std::uint64_t uploadedTextureBytes_ = limits::kMaxTextureBytes;  // its bricks' limit
};

// ---- postfx on arrays ----

cv::Mat1b maskFromArray(const py::array& lines, const std::string& function) {
  if (lines.ndim() != 2) throw InputError(function + ": expected a 2-dimensional line mask");
  // The image side of a render (--size), checked before the array is copied or converted.
  if (lines.shape(0) < 1 || lines.shape(1) < 1 || lines.shape(0) > limits::kMaxImageSide ||
      lines.shape(1) > limits::kMaxImageSide) {
    throw InputError(function + ": a " + std::to_string(lines.shape(0)) + "x" +
                     std::to_string(lines.shape(1)) + " mask; each side must be 1 .. " +
                     std::to_string(limits::kMaxImageSide) + " pixels");
  }
  const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast> mask(lines);
  cv::Mat1b result(int(mask.shape(0)), int(mask.shape(1)));
  std::memcpy(result.data, mask.data(), result.total());
  return result;
}

cv::Mat1f depthFromArray(const py::array& depth, cv::Size size, const std::string& function) {
  const py::array_t<float, py::array::c_style | py::array::forcecast> values(depth);
  if (values.ndim() != 2 || values.shape(0) != size.height || values.shape(1) != size.width) {
    throw InputError(function + ": depth must be a 2-dimensional array of the image's shape");
  }
  cv::Mat1f result(size);
  std::memcpy(result.data, values.data(), result.total() * sizeof(float));
  return result;
}

void checkWidth(double width, const std::string& what) {
  if (!(width > 0 && width <= limits::kMaxLineWidth)) {
    throw InputError("vsil.broaden: " + what + " must be in (0, " +
                     std::to_string(int(limits::kMaxLineWidth)) + "] pixels");
  }
}

// The FFT broadening's buffers, bounded as a render's image (limits::renderImageBytes), against
// the default --max-memory.
void checkBroadenMemory(cv::Size size, double width) {
  limits::checkMemory(
      "vsil.broaden: a " + std::to_string(size.height) + "x" + std::to_string(size.width) + " mask",
      limits::renderImageBytes({size.width, size.height}, width), limits::defaultMemoryBytes());
}

py::array broaden(const py::array& lines, std::optional<double> width,
                  std::optional<double> widthNear, std::optional<double> widthFar,
                  std::optional<py::array> depth) {
  const std::string function = "vsil.broaden";
  const cv::Mat1b mask = maskFromArray(lines, function);
  cv::Mat1b result;
  if (width) {
    if (widthNear || widthFar) {
      throw InputError(function + ": give width, or width_near and width_far, not both");
    }
    checkWidth(*width, "width");
    checkBroadenMemory(mask.size(), *width);
    py::gil_scoped_release release;
    FftGaussianBlur blur;
    result = broadenMask(mask, *width, blur);
  } else {
    if (!widthNear || !widthFar || !depth) {
      throw InputError(function + ": give width, or width_near, width_far and depth");
    }
    checkWidth(*widthNear, "width_near");
    checkWidth(*widthFar, "width_far");
    checkBroadenMemory(mask.size(), std::max(*widthNear, *widthFar));
    const cv::Mat1f depths = depthFromArray(*depth, mask.size(), function);
    py::gil_scoped_release release;
    FftGaussianBlur blur;
    result = broadenLines(
        lineWidthsFromDepth(mask, depths, WidthLaw::depthAdaptive(*widthNear, *widthFar)), blur);
  }
  return arrayFromMat<std::uint8_t>(result, 1);
}

py::dict measureWidth(const py::array& image, std::optional<py::array> depth, int bins,
                      double binWidth) {
  const std::string function = "vsil.measure_width";
  if (image.ndim() != 2) {
    throw InputError(function + ": expected a 2-dimensional line mask (non-zero = line)");
  }
  if (!(bins >= 1 && bins <= 1000)) throw InputError(function + ": bins must be in 1 .. 1000");
  if (!(binWidth > 0)) throw InputError(function + ": bin_width must be positive");
  const cv::Mat1b mask = maskFromArray(image, function);
  const auto samples = measureLineWidths(mask);
  std::vector<double> widths;
  for (const auto& s : samples) widths.push_back(s.width);
  nlohmann::json report = {{"widths", widthStatisticsJson(summarizeWidths(widths, binWidth))}};
  if (depth) {
    const cv::Mat1f depths = depthFromArray(*depth, mask.size(), function);
    report["by_depth"] = depthBinsJson(widthAgainstDepth(samples, depths, bins));
  }
  py::array_t<double> table({py::ssize_t(samples.size()), py::ssize_t(3)});
  auto rows = table.mutable_unchecked<2>();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    rows(i, 0) = samples[i].pixel.x;
    rows(i, 1) = samples[i].pixel.y;
    rows(i, 2) = samples[i].width;
  }
  py::dict result = jsonToPython(report);
  result["samples"] = table;
  return result;
}

}  // namespace
}  // namespace vsil::python

PYBIND11_MODULE(vsil, m) {
  using namespace vsil;
  using namespace vsil::python;
  m.doc() = "vsil: volume illustration (exact silhouettes, Ebert-Rheingans, DEMIP) offscreen";

  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const UnavailableError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<PyVolume>(m, "Volume", "A scalar volume; .data is a numpy view (z, y, x)")
      .def(py::init(&wrapArray), py::arg("array"),
           py::arg("spacing") = std::vector<double>{1.0, 1.0, 1.0}, py::arg("name") = "array",
           "Wraps a C-contiguous (z, y, x) array of uint8, int8, uint16, int16 or float32 "
           "without copying; spacing is (x, y, z)")
      .def_property_readonly("data", &dataOf)
      .def_property_readonly("dims",
                             [](const PyVolume& v) {
                               return py::make_tuple(v.volume->dims.x, v.volume->dims.y,
                                                     v.volume->dims.z);
                             })
      .def_property_readonly("spacing",
                             [](const PyVolume& v) {
                               return py::make_tuple(v.volume->spacing.x, v.volume->spacing.y,
                                                     v.volume->spacing.z);
                             })
      .def_property_readonly("name", [](const PyVolume& v) { return v.volume->name; })
      .def_property_readonly("source", [](const PyVolume& v) { return v.volume->source; })
      .def_property_readonly(
          "format", [](const PyVolume& v) { return v.volume->format; },
          "the file's format and variant, '' for generated volumes")
      .def_property_readonly(
          "warnings", [](const PyVolume& v) { return v.volume->warnings; },
          "what reading the file warned about (also issued as UserWarning)")
      .def_property_readonly("dtype", [](const PyVolume& v) { return dtypeOf(v.volume->type()); })
      .def_property_readonly("value_range",
                             [](const PyVolume& v) {
                               const ValueRange range = valueRange(*v.volume);
                               return py::make_tuple(range.min, range.max);
                             })
      .def("__repr__", [](const PyVolume& v) {
        const Volume& volume = *v.volume;
        return "<vsil.Volume " + volume.name + " " + std::to_string(volume.dims.x) + "x" +
               std::to_string(volume.dims.y) + "x" + std::to_string(volume.dims.z) + " " +
               sampleTypeName(volume.type()) + ">";
      });

  m.def("load", &load, py::arg("path"),
        "Reads a volume file or generates a gen: volume; keywords: the volume flags of "
        "`vsil render` (dims, type, spacing, endian, crop, stride, max_memory)");
  m.def(
      "generate",
      [](const std::string& name, int size) {
        return load("gen:" + name + ":" + std::to_string(size), py::kwargs());
      },
      py::arg("name"), py::arg("size") = 128, "A procedural volume, as INPUT gen:NAME:SIZE");

  py::class_<Frame>(m, "Frame", "One rendered frame")
      .def_readonly("image", &Frame::image, "H x W x 4 uint8, RGBA")
      .def_readonly("state", &Frame::state, "H x W uint8 pixel states")
      .def_readonly("depth", &Frame::depth, "H x W float32 normalized depth, NaN where none")
      .def_readonly("metadata", &Frame::metadata, "what `vsil render --meta-out` writes")
      .def_readonly("warnings", &Frame::warnings);

  py::class_<PythonRenderer>(m, "Renderer",
                             "One GL context; keywords gl, gl_device as `vsil render`")
      .def(py::init<const py::kwargs&>())
      .def("render", &PythonRenderer::render, py::arg("volume"),
           "Renders a Volume (or a path or gen: spec); keywords: every flag of `vsil render` "
           "by its name with _ for - (iso=40, width_near=4, view=(30, 20), size=(640, 480))")
      .def("upload", &PythonRenderer::upload, py::arg("volume"),
           "Uploads the volume again (after its samples changed in place)");

  m.def("broaden", &broaden, py::arg("lines"), py::kw_only(), py::arg("width") = py::none(),
        py::arg("width_near") = py::none(), py::arg("width_far") = py::none(),
        py::arg("depth") = py::none(),
        "Broadens one-pixel lines (non-zero pixels) to `width`, or from width_near to "
        "width_far by `depth` (normalized, NaN where none); returns a 0/255 uint8 mask");
  m.def("measure_width", &measureWidth, py::arg("lines"), py::kw_only(),
        py::arg("depth") = py::none(), py::arg("bins") = 10, py::arg("bin_width") = 1.0,
        "Line widths of a mask (non-zero = line) on its medial axis: the statistics "
        "`vsil measure-width --json` writes, by_depth with `depth`, and samples (x, y, width)");
}
