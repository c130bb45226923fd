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
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
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
#include "cli/cli_parse.h"
#include "cli/cli_render_options.h"
#include "cli/volume_summary.h"
#include "core/error.h"
#include "core/image_file.h"
#include "core/json_input.h"
#include "core/limits.h"
#include "core/number_pair.h"
#include "core/version.h"
#include "core/volume.h"
#include "io/sample_sink.h"
#include "io/volume_loader.h"
#include "job/animation.h"
#include "job/gl_turn.h"
#include "job/render_job.h"
#include "postfx/broaden.h"
#include "postfx/line_width.h"
#include "slicing/technique_table.h"
#include "video/video_file.h"

namespace py = pybind11;

namespace vsil::python {
namespace {

// Bytes as Python text, as Python decodes file names (os.fsdecode): UTF-8, and a byte that is
// not (a Linux file name may hold one) as a lone surrogate, so that messages and warnings
// naming such a file reach Python instead of failing to decode.
py::str fsText(const std::string& bytes) {
  PyObject* text = PyUnicode_DecodeFSDefaultAndSize(bytes.data(), py::ssize_t(bytes.size()));
  if (!text) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(text);
}

// The bytes a str stands for, as os.fsencode gives them: UTF-8, with the bytes of a file name
// that is not UTF-8 (Python holds them as lone surrogates) back as they were.
std::string fsBytes(const py::handle& text) {
  return py::module_::import("os").attr("fsencode")(text).cast<std::string>();
}

// A UserWarning at the caller's line (PyErr_WarnEx's stack level 1).
// A UserWarning attributed to the caller's line: past the frames of the vsil package's own
// Python wrappers (warnings' stacklevel counts them), not to vsil/__init__.py.
void warnUser(const std::string& message) {
  const py::object sys = py::module_::import("sys");
  const std::string package = py::str(
      py::module_::import("os.path").attr("dirname")(py::module_::import("vsil").attr("__file__")));
  int level = 1;
  for (py::object frame = sys.attr("_getframe")(0); !frame.is_none();
       frame = frame.attr("f_back")) {
    const std::string file = py::str(frame.attr("f_code").attr("co_filename"));
    if (!file.starts_with(package + "/")) break;
    ++level;
  }
  py::module_::import("warnings")
      .attr("warn")(fsText(message), py::handle(PyExc_UserWarning), level);
}

template <typename Json>
py::object jsonToPython(const Json& json) {
  return py::module_::import("json").attr("loads")(jsonText(json));
}

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
  // By equality: a native dtype may be another object than numpy's canonical one ('=f4').
  if (!array.dtype().equal(py::dtype::of<C>())) {
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

// The supported dtype nearest to an array's: float64 and float16 -> float32, integers wider
// than 16 bits -> float32 (exact while |v| <= 2^24), bool -> uint8; supported ones as they are
// (in native byte order). None for dtypes no number converts from (complex, object, str).
std::optional<py::dtype> supportedDtype(const py::dtype& dtype) {
  const char kind = py::str(dtype.attr("kind")).cast<std::string>()[0];
  const py::ssize_t size = dtype.itemsize();
  if (kind == 'b') return py::dtype::of<std::uint8_t>();
  if (kind == 'f') return py::dtype::of<float>();
  if (kind == 'i' && size == 1) return py::dtype::of<std::int8_t>();
  if (kind == 'i' && size == 2) return py::dtype::of<std::int16_t>();
  if (kind == 'u' && size == 1) return py::dtype::of<std::uint8_t>();
  if (kind == 'u' && size == 2) return py::dtype::of<std::uint16_t>();
  if (kind == 'i' || kind == 'u') return py::dtype::of<float>();
  return std::nullopt;
}

// The array as vsil reads it: shared when it is C-contiguous, of a supported dtype and in native
// byte order; otherwise copied once into one (numpy.ascontiguousarray), with a UserWarning that
// says why (the dtype converted, the bytes swapped, the strides).
py::array samplesArray(const py::array& array) {
  const py::dtype dtype = array.dtype();
  const std::optional<py::dtype> target = supportedDtype(dtype);
  const std::string from = py::str(dtype.attr("name"));
  if (!target) {
    throw InputError("vsil.Volume: samples of dtype " + from +
                     " are not supported (uint8, int8, uint16, int16, float32, or a real or "
                     "boolean dtype that converts to one)");
  }
  std::vector<std::string> why;
  if (from != std::string(py::str(target->attr("name")))) {
    why.push_back(from + " samples converted to " + std::string(py::str(target->attr("name"))) +
                  (from.find("int") != std::string::npos ? " (exact while |v| <= 2^24)" : ""));
  }
  if (!dtype.attr("isnative").cast<bool>()) why.push_back("big-endian samples byte-swapped");
  if (!(array.flags() & py::array::c_style)) {
    why.push_back("a non-C-contiguous array (strides " +
                  std::string(py::str(array.attr("strides"))) + ") copied into C order");
  }
  if (why.empty()) return array;
  if (py::str(dtype.attr("kind")).cast<std::string>() == "f" && dtype.itemsize() > 4) {
    // A finite sample beyond float32 turns infinite in the copy, which would call it infinite:
    // named here as the readers name it (io/sample_sink.cpp).
    const py::module_ np = py::module_::import("numpy");
    const py::object beyond = np.attr("logical_and")(
        np.attr("isfinite")(array),
        np.attr("greater")(np.attr("abs")(array), double(std::numeric_limits<float>::max())));
    const py::array_t<py::ssize_t> at = np.attr("flatnonzero")(beyond);
    if (at.size() > 0) {
      const py::ssize_t index = at.at(0);
      io::checkFloat32("vsil.Volume", std::uint64_t(index),
                       np.attr("ravel")(array).attr("__getitem__")(index).cast<double>());
    }
  }
  std::string message = "vsil.Volume: ";
  for (std::size_t i = 0; i < why.size(); ++i) message += (i ? "; " : "") + why[i];
  message += ": one copy of " + std::to_string(array.size() * target->itemsize()) +
             " bytes (the Volume reads the copy, not the array)";
  warnUser(message);
  return py::module_::import("numpy").attr("ascontiguousarray")(array, *target);
}

PyVolume wrapArray(const py::array& given, std::vector<double> spacing, std::string name) {
  if (given.ndim() != 3) {
    throw InputError("vsil.Volume: expected a 3-dimensional array (z, y, x), got " +
                     std::to_string(given.ndim()) + " dimensions");
  }
  if (spacing.size() != 3 || !(spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0)) {
    throw InputError("vsil.Volume: spacing must be three positive numbers (x, y, z)");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (given.shape(axis) < 1 || given.shape(axis) > limits::kMaxVolumeSide) {
      throw InputError("vsil.Volume: each axis must have 1 .. " +
                       std::to_string(limits::kMaxVolumeSide) + " samples, not " +
                       std::to_string(given.shape(axis)));
    }
  }
  const py::array array = samplesArray(given);
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
    throw std::logic_error("vsil.Volume: samplesArray gave an unsupported dtype");
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

// A Python-level error that is not a ValueError (the translator below raises it as is).
struct PythonTypeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// A volume file that is not there: FileNotFoundError(ENOENT, the CLI's message, path).
struct VolumeNotFound : std::runtime_error {
  VolumeNotFound(const std::string& message, std::string path)
      : std::runtime_error(message), path(std::move(path)) {}
  std::string path;
};

// One keyword as Python sees it, derived from the CLI option it becomes: the technique table's
// declaration where the option is a technique option (its kind, default, choices), else what
// the option's registration says (flag or value, captured default, CLI11's type name).
struct Keyword {
  std::string key;   // width_near
  std::string flag;  // --width-near
  std::string kind;  // switch, number, integer, choice, text, list
  std::string help;
  std::string group;
  py::object defaultValue = py::none();  // None: none, or derived (the help says how)
  std::vector<std::string> choices;
  int numberCount = 0;  // text holding this many numbers ("AZ,EL": 2); 0 otherwise
};

// A text keyword of the module's own (not a flag): animate's view_from, video, sweep ends.
Keyword textKeyword(std::string key) {
  Keyword keyword;
  keyword.key = std::move(key);
  keyword.kind = "text";
  return keyword;
}

const OptionSpec* techniqueSpec(const std::string& name) {
  static const std::map<std::string, const OptionSpec*> specs = [] {
    std::map<std::string, const OptionSpec*> all;
    for (const auto& info : techniqueTable()) {
      for (const auto& spec : info.options) all.emplace(spec.name, &spec);
    }
    return all;
  }();
  const auto it = specs.find(name);
  return it == specs.end() ? nullptr : it->second;
}

// "512x512" -> (512, 512), "30,20" -> (30, 20), "1" -> 1.0, other text as it is.
py::object defaultFromText(const std::string& text, std::string_view kind) {
  if (text.empty()) return py::none();
  std::string list = text;
  const auto x = list.find('x');
  if (x != std::string::npos && list.find('x', x + 1) == std::string::npos) list[x] = ',';
  if (const auto numbers = parseNumberList(list)) {
    if (numbers->size() == 1 && kind == "integer") return py::int_(std::lround(numbers->front()));
    if (numbers->size() == 1 && (kind == "number" || kind == "integer")) {
      return py::float_(numbers->front());
    }
    if (numbers->size() > 1) {
      py::tuple tuple(numbers->size());
      for (std::size_t i = 0; i < numbers->size(); ++i) {
        const double n = (*numbers)[i];
        tuple[i] = n == std::floor(n) && std::abs(n) < 1e15 ? py::object(py::int_(std::llround(n)))
                                                            : py::object(py::float_(n));
      }
      return tuple;
    }
  }
  return py::str(text);
}

Keyword describeKeyword(const CLI::Option& option) {
  Keyword keyword;
  keyword.flag = "--" + option.get_single_name();
  keyword.key = option.get_single_name();
  for (char& c : keyword.key) c = c == '-' ? '_' : c;
  keyword.help = option.get_description();
  keyword.group = option.get_group();
  if (const OptionSpec* spec = techniqueSpec(option.get_single_name())) {
    static const char* const kinds[] = {"number", "integer", "choice", "text", "switch", "list"};
    keyword.kind = kinds[int(spec->kind)];
    keyword.choices = spec->choices;
    keyword.numberCount = spec->numberCount;
    if (spec->defaultValue && spec->kind != OptionKind::List) {
      std::visit(
          [&](const auto& value) {
            using T = std::decay_t<decltype(value)>;
            if constexpr (std::is_same_v<T, bool>) {
              keyword.defaultValue = py::bool_(value);
            } else if constexpr (std::is_same_v<T, double>) {
              keyword.defaultValue = spec->kind == OptionKind::Integer
                                         ? py::object(py::int_(std::lround(value)))
                                         : py::object(py::float_(value));
            } else if constexpr (std::is_same_v<T, std::string>) {
              keyword.defaultValue = defaultFromText(value, "text");
            }
          },
          *spec->defaultValue);
    }
    return keyword;
  }
  if (option.get_single_name() == "technique") {  // a name from the technique table
    keyword.kind = "choice";
    keyword.choices = techniqueNames();
    keyword.defaultValue = py::str(option.get_default_str());
    return keyword;
  }
  if (option.get_expected_min() == 0 || option.get_type_size() == 0) {
    keyword.kind = "switch";
    keyword.defaultValue = py::bool_(false);
    return keyword;
  }
  // CLI11's type names: FLOAT, INT, INT:NONNEGATIVE, TEXT, TEXT:{a,b,c}.
  const std::string type = option.get_type_name();
  keyword.kind = type.rfind("FLOAT", 0) == 0 ? "number"
                 : type.rfind("INT", 0) == 0 ? "integer"
                                             : "text";
  if (const auto open = type.find(":{"); open != std::string::npos) {
    keyword.kind = "choice";
    std::string list = type.substr(open + 2, type.size() - open - 3);
    for (std::size_t at = 0; at <= list.size();) {
      const std::size_t comma = std::min(list.find(',', at), list.size());
      keyword.choices.push_back(list.substr(at, comma - at));
      at = comma + 1;
    }
  }
  keyword.defaultValue = defaultFromText(option.get_default_str(), keyword.kind);
  return keyword;
}

// The keywords of `app` in registration order, less those in `except` (by key).
std::vector<Keyword> keywordsOf(const CLI::App& app, const std::vector<std::string>& except = {}) {
  std::vector<Keyword> keywords;
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_lnames().empty() || option->get_single_name() == "help") continue;
    Keyword keyword = describeKeyword(*option);
    if (std::find(except.begin(), except.end(), keyword.key) != except.end()) continue;
    keywords.push_back(std::move(keyword));
  }
  return keywords;
}

std::string typeNameOf(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__"));
}

bool isNumber(const py::handle& value) {
  // A numpy array has __float__ (for one element) but prints as its repr: only a 0-d one is a
  // number; a 1-d one is a sequence (valueText).
  if (py::isinstance<py::array>(value)) {
    return py::reinterpret_borrow<py::array>(value).ndim() == 0;
  }
  return !py::isinstance<py::bool_>(value) && !py::isinstance<py::str>(value) &&
         (PyLong_Check(value.ptr()) || PyFloat_Check(value.ptr()) || PyIndex_Check(value.ptr()) ||
          py::hasattr(value, "__float__"));
}

// ---- native values: each converted here, once, into the text its flag takes ----

bool isSequence(const py::handle& value) {
  return py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value);
}

// vsil.Volume(array, spacing, name): arguments of the wrong type raise one TypeError line
// naming what each takes (pybind11's own spans several lines and lists the signature).
PyVolume makeVolume(const py::object& array, const py::object& spacing, const py::object& name) {
  const std::string function = "vsil.Volume";
  // Nested lists convert as numpy would convert them.
  if (!py::isinstance<py::array>(array) && !isSequence(array)) {
    throw PythonTypeError(function + ": array takes a numpy array (z, y, x), not " +
                          typeNameOf(array));
  }
  const bool numbers = (isSequence(spacing) || py::isinstance<py::array>(spacing)) &&
                       py::len(spacing) == 3 &&
                       std::all_of(spacing.begin(), spacing.end(),
                                   [](const py::handle& item) { return isNumber(item); });
  if (!numbers) {
    const std::string given = py::repr(spacing);
    throw PythonTypeError(function + ": spacing takes three numbers (x, y, z), not " +
                          typeNameOf(spacing) + " " +
                          (given.size() > 60 ? given.substr(0, 60) + "..." : given));
  }
  if (!py::isinstance<py::str>(name)) {
    throw PythonTypeError(function + ": name takes a str, not " + typeNameOf(name));
  }
  std::vector<double> values;
  for (const py::handle item : spacing)
    values.push_back(py::float_(py::reinterpret_borrow<py::object>(item)));
  return wrapArray(py::array::ensure(array), values, name.cast<std::string>());
}

// The colour flags (--background, --line-color, --fill-color, --color, --sketch-color).
bool isColourKeyword(const Keyword& keyword) {
  return keyword.key == "background" || keyword.key.ends_with("color");
}

// (r, g, b) or (r, g, b, a) in [0, 1], matplotlib's convention -> "#rrggbb[aa]", each channel
// round(255 v): the text parseColor reads back to the same 8-bit channels.
std::string colourText(const Keyword& keyword, const py::handle& value,
                       const std::string& function) {
  const py::sequence channels = py::reinterpret_borrow<py::sequence>(value);
  if (channels.size() != 3 && channels.size() != 4) {
    throw InputError(function + ": " + keyword.key + " takes 3 or 4 numbers (r, g, b[, a]) in " +
                     "[0, 1], not " + std::to_string(channels.size()));
  }
  std::string text = "#";
  for (const py::handle channel : channels) {
    if (!isNumber(channel)) {
      throw PythonTypeError(function + ": " + keyword.key + " takes numbers in [0, 1], not " +
                            typeNameOf(channel) + " items");
    }
    const double v = py::float_(py::reinterpret_borrow<py::object>(channel));
    if (!(v >= 0 && v <= 1)) {
      throw InputError(function + ": " + keyword.key + " takes channels in [0, 1], not " +
                       std::string(py::str(channel)) + " (for 0 .. 255 values divide by 255)");
    }
    char hex[3];
    std::snprintf(hex, sizeof hex, "%02x", int(std::lround(v * 255)));
    text += hex;
  }
  return text;
}

bool isSliceOrSlices(const py::handle& value) {
  if (py::isinstance<py::slice>(value)) return true;
  if (!py::isinstance<py::tuple>(value) || py::len(value) == 0) return false;
  for (const py::handle item : value) {
    if (!py::isinstance<py::slice>(item)) return false;
  }
  return true;
}

// A slice or a tuple of up to 3 slices in numpy's axis order (z, y, x), as they index
// Volume.data (missing trailing axes whole, as numpy's a[s]) -> --crop "X0:X1,Y0:Y1,Z0:Z1":
// load(path, crop=numpy.s_[2:5, :, 1:4]).data == load(path).data[2:5, :, 1:4]. Negative
// bounds are not resolved against the size (the flag refuses them), and a step is stride's.
std::string cropText(const py::handle& value, const std::string& function) {
  std::vector<py::object> slices;
  if (py::isinstance<py::slice>(value)) {
    slices.push_back(py::reinterpret_borrow<py::object>(value));
  } else {
    for (const py::handle item : value) slices.push_back(py::reinterpret_borrow<py::object>(item));
  }
  if (slices.size() > 3) {
    throw InputError(function + ": crop takes up to 3 slices (z, y, x), not " +
                     std::to_string(slices.size()));
  }
  std::string axes[3];  // x, y, z
  for (std::size_t i = 0; i < 3; ++i) {
    std::string& axis = axes[2 - i];
    if (i >= slices.size()) {
      axis = ":";
      continue;
    }
    const py::object& slice = slices[i];
    const py::object step = slice.attr("step");
    if (!step.is_none() && !step.equal(py::int_(1))) {
      throw InputError(function +
                       ": crop's slices take no step (read every Nth sample with "
                       "stride=N)");
    }
    const auto bound = [&](const char* which) {
      const py::object b = slice.attr(which);
      if (b.is_none()) return std::string();
      if (!PyIndex_Check(b.ptr())) {
        throw PythonTypeError(function + ": crop's slice bounds are integers, not " +
                              typeNameOf(b));
      }
      return std::string(py::str(py::reinterpret_steal<py::object>(PyNumber_Index(b.ptr()))));
    };
    axis = bound("start") + ":" + bound("stop");
  }
  return axes[0] + "," + axes[1] + "," + axes[2];
}

// param={"k_ty": 0.4, "k_ds": 0.5} -> "k_ty=0.4,k_ds=0.5".
std::string parameterText(const py::dict& parameters) {
  std::string text;
  for (const auto& [name, value] : parameters) {
    text +=
        (text.empty() ? "" : ",") + std::string(py::str(name)) + "=" + std::string(py::str(value));
  }
  return text;
}

bool isDictOrDicts(const py::handle& value) {
  if (py::isinstance<py::dict>(value)) return true;
  if (!isSequence(value) || py::len(value) == 0) return false;
  for (const py::handle item : value) {
    if (!py::isinstance<py::dict>(item)) return false;
  }
  return true;
}

// One value as the command line writes it: str as it is (rule text too: --rules takes it),
// os.PathLike by os.fspath, a number by Python's shortest round-trip text, an RGB(A) tuple for a
// colour, slices for crop, a dict for param, a dict or list of dicts (tf=[{"value": 0, ...}],
// style={...}) as its JSON text, a sequence of numbers or texts joined ("30,20"; "640x480" for
// size, "8x7x6" for dims). Anything else is a TypeError naming the keyword.
std::string valueText(const Keyword& keyword, const py::handle& value,
                      const std::string& function) {
  if (py::isinstance<py::str>(value)) return fsBytes(value);
  if (keyword.key == "crop" && isSliceOrSlices(value)) return cropText(value, function);
  if (isColourKeyword(keyword) && isSequence(value)) return colourText(keyword, value, function);
  if (keyword.key == "param" && py::isinstance<py::dict>(value)) {
    return parameterText(py::reinterpret_borrow<py::dict>(value));
  }
  if (keyword.kind == "text" && isDictOrDicts(value)) {
    // numpy's numbers and arrays as the Python numbers and lists they hold (a transfer
    // function from numpy.linspace); anything else JSON lacks is a TypeError naming the keyword.
    const py::object numpyGeneric = py::module_::import("numpy").attr("generic");
    const py::cpp_function asJson([=, key = keyword.key](const py::handle& item) -> py::object {
      if (py::isinstance<py::array>(item) || py::isinstance(item, numpyGeneric)) {
        return item.attr("tolist")();
      }
      throw PythonTypeError(function + ": " + key + " takes JSON values (numbers, texts, lists, " +
                            "dicts), not " + typeNameOf(item));
    });
    try {
      return py::str(py::module_::import("json").attr("dumps")(value, py::arg("default") = asJson,
                                                               py::arg("allow_nan") = false));
    } catch (py::error_already_set& e) {
      // NaN and infinities (not JSON), keys that are not texts: one line naming the keyword.
      if (e.matches(PyExc_ValueError)) {
        throw InputError(function + ": " + keyword.key + " takes finite numbers, not NaN or inf");
      }
      if (e.matches(PyExc_TypeError)) {
        const std::string why = py::str(e.value());
        if (why.starts_with("keys must be")) {
          throw PythonTypeError(function + ": " + keyword.key + "'s dict keys must be texts");
        }
      }
      throw;
    }
  }
  if (py::hasattr(value, "__fspath__")) {
    return fsBytes(py::module_::import("os").attr("fspath")(value));
  }
  if (isNumber(value)) return py::str(value);
  const bool vector =
      py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() == 1;
  if (keyword.kind != "number" && keyword.kind != "integer" &&
      (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value) || vector)) {
    std::string joined;
    bool first = true;
    for (const py::handle item : value) {
      if (!isNumber(item) && !py::isinstance<py::str>(item)) {
        throw PythonTypeError(function + ": " + keyword.key + " takes numbers or texts, not " +
                              typeNameOf(item) + " items");
      }
      // --size WxH and --dims XxYxZ are the flags written with x; every other list with commas.
      const bool byX = keyword.key == "size" || keyword.key == "dims";
      joined += (first ? "" : byX ? "x" : ",") + std::string(py::str(item));
      first = false;
    }
    return joined;
  }
  const std::string expected = keyword.kind == "number"    ? "a number"
                               : keyword.kind == "integer" ? "an integer"
                                                           : "a str, a number or a tuple";
  throw PythonTypeError(function + ": " + keyword.key + " takes " + expected + ", not " +
                        typeNameOf(value));
}

// The keyword's flag and value(s) for the command line: True -> the bare flag of a switch; None
// -> nothing (the default); a list option given a list of texts or tuples -> the flag once per
// item (light=[(30, 70), (-40, 10)]).
void appendFlag(std::vector<std::string>& args, const Keyword& keyword, const py::handle& value,
                const std::string& function) {
  if (value.is_none()) return;
  if (keyword.kind == "switch") {
    if (!py::isinstance<py::bool_>(value)) {
      throw PythonTypeError(function + ": " + keyword.key + " takes True or False, not " +
                            typeNameOf(value));
    }
    if (value.cast<bool>()) args.push_back(keyword.flag);
    return;
  }
  if (py::isinstance<py::bool_>(value)) {
    throw PythonTypeError(function + ": " + keyword.key + " takes a value, not a bool");
  }
  if (keyword.kind == "list" &&
      (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value))) {
    bool ofItems = false;
    for (const py::handle item : value) ofItems = ofItems || !isNumber(item);
    if (ofItems) {
      for (const py::handle item : value) {
        args.push_back(keyword.flag);
        args.push_back(valueText(keyword, item, function));
      }
      return;
    }
  }
  args.push_back(keyword.flag);
  args.push_back(valueText(keyword, value, function));
}

// Parses `kwargs` with `app`'s options; a keyword with no flag of that name is a TypeError
// naming it, as Python's own for an unexpected keyword argument.
void parseKeywords(CLI::App& app, const py::kwargs& kwargs, const std::string& function) {
  cli::readNumbersAsDecimal(app);
  std::vector<std::string> args;
  for (const auto& [key, value] : kwargs) {
    const std::string name = key.cast<std::string>();
    std::string flag = "--" + name;
    for (char& c : flag) c = c == '_' ? '-' : c;
    const CLI::Option* option =
        name.empty() || name == "help" || name.find('-') != std::string::npos
            ? nullptr
            : app.get_option_no_throw(flag);
    if (!option) throw PythonTypeError(function + ": unknown keyword '" + name + "'");
    appendFlag(args, describeKeyword(*option), value, function);
  }
  std::reverse(args.begin(), args.end());  // CLI11 parses a vector from its back
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw InputError(function + ": " + cli::parseErrorText(e));
  }
}

// The keyword tables as Python reads them (vsil/__init__.py: signatures and help; make_stub.py:
// the stub): one dict per keyword, in the CLI's order.
py::list keywordTable(const std::string& function) {
  CLI::App app;
  std::vector<std::string> except;
  cli::RenderFlags render;
  cli::VolumeOptions volume;
  cli::GlOptions gl;
  if (function == "render") {
    cli::addRenderOptions(app, render);
    except = {"gl", "gl_device"};
  } else if (function == "load") {
    cli::addVolumeOptions(app, volume);
    except = {"max_texture_mib"};  // render's and add_volume's (load refuses it)
  } else if (function == "Renderer") {
    cli::addGlOptions(app, gl);
  } else {
    throw InputError("vsil._keywords: no table '" + function + "' (render, load, Renderer)");
  }
  py::list table;
  for (const Keyword& keyword : keywordsOf(app, except)) {
    py::dict row;
    row["key"] = keyword.key;
    row["flag"] = keyword.flag;
    row["kind"] = keyword.kind;
    row["help"] = keyword.help;
    row["group"] = keyword.group;
    row["default"] = keyword.defaultValue;
    row["choices"] = keyword.choices;
    row["number_count"] = keyword.numberCount;
    table.append(row);
  }
  return table;
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

// Runs `load`; an InputError for a volume path that does not exist becomes VolumeNotFound (the
// same message: FileNotFoundError in Python).
template <typename Load>
auto loadOrNotFound(Load&& load, const std::string& spec) {
  try {
    return load();
  } catch (const InputError& e) {
    std::error_code error;
    if (spec.rfind("gen:", 0) != 0 && !std::filesystem::exists(spec, error)) {
      throw VolumeNotFound(e.what(), spec);
    }
    throw;
  }
}

PyVolume load(const py::object& path, const py::kwargs& kwargs) {
  if (!py::isinstance<py::str>(path)) {
    throw PythonTypeError("vsil.load: expected a path or a gen: spec, not " + typeNameOf(path));
  }
  const std::string spec = fsBytes(path);
  // Accepted and ignored before (round 16): how a volume is cut into textures is decided where
  // it is uploaded.
  if (kwargs.contains("max_texture_mib")) {
    throw PythonTypeError(
        "vsil.load: max_texture_mib is a keyword of render and add_volume, "
        "where the volume is uploaded, not of load");
  }
  const LoadOptions options = loadOptionsFromKeywords(kwargs, "vsil.load");
  Volume loaded;
  {
    py::gil_scoped_release release;
    loaded = loadOrNotFound([&] { return loadVolume(spec, options); }, spec);
  }
  for (const std::string& warning : loaded.warnings) {
    warnUser(warning);
  }
  return {std::make_shared<Volume>(std::move(loaded))};
}

// What `vsil info VOLUME --json` prints (cli/volume_summary.h), for a path or gen: spec read
// with the volume keywords, or for a Volume.
py::object info(const py::object& input, const py::kwargs& kwargs) {
  if (py::isinstance<PyVolume>(input)) {
    if (kwargs.size() > 0) {
      throw PythonTypeError("vsil.info: the volume keywords apply when a file is read");
    }
    const std::shared_ptr<Volume> volume = input.cast<const PyVolume&>().volume;
    nlohmann::ordered_json json;
    {
      py::gil_scoped_release release;
      // Its array may have changed since it was wrapped: NaN is refused here as render does.
      requireFiniteSamples(*volume);
      json = cli::summaryJson(*volume, cli::summarize(*volume));
    }
    return jsonToPython(json);
  }
  if (!py::isinstance<py::str>(input)) {
    throw PythonTypeError("vsil.info: expected a vsil.Volume, a path or a gen: spec, not " +
                          typeNameOf(input));
  }
  const std::string spec = fsBytes(input);
  const LoadOptions options = cli::summaryLoadOptions(loadOptionsFromKeywords(kwargs, "vsil.info"));
  Volume loaded;
  nlohmann::ordered_json json;
  {
    py::gil_scoped_release release;
    loaded = loadOrNotFound([&] { return loadVolume(spec, options); }, spec);
    json = cli::summaryJson(loaded, cli::summarize(loaded));
  }
  for (const std::string& warning : loaded.warnings) {
    warnUser(warning);
  }
  return jsonToPython(json);
}

// ---- rendering ----

struct Frame {
  py::array image;   // H x W x 4 uint8, RGBA
  py::object state;  // H x W uint8, PixelState (0 empty, 1 filled, 2 contour, 3 silhouette); None
  py::object depth;  // H x W float32, normalized depth, NaN where none; None
                     // (None: the technique makes none, as TechniqueInfo::outputs says)
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

// ---- GL turns ----

// One turn (job/gl_turn.h: every GL call of the module, from any thread and any Renderer, under
// one lock; renders from several threads wait their turn, llvmpipe uses every core for each
// frame anyway). It releases the GIL first, then waits for the lock. Never the other way round:
// a thread holding the lock may need the GIL (the last reference to a numpy array a volume
// borrowed), so a thread holding the GIL must not wait for the lock.
class GlTurn {
 public:
  explicit GlTurn(RenderJob* job) : turn_(job) {}
  void setJob(RenderJob* job) { turn_.setJob(job); }  // a job made during the turn

 private:
  py::gil_scoped_release release_;  // destroyed last: the GIL comes back after the unlock
  vsil::GlTurn turn_;
};

// A RenderJob and what its textures hold: the volume, when given as a Volume, and its bricks'
// limit. Read and written during turns only.
struct Slot {
  std::unique_ptr<RenderJob> job;
  std::shared_ptr<Volume> uploaded;
  std::uint64_t uploadedTextureBytes = limits::kMaxTextureBytes;
};

// What every call on a closed Renderer raises (ValueError).
[[noreturn]] void throwClosed() {
  throw InputError("vsil.Renderer: this renderer is closed");
}

// The turn of a slot's job. Its job is looked at once the turn is held: close() ends the main
// slot's job in a turn of its own, which may come while this thread waits for the lock (a
// Renderer closed from another thread); then this raises "closed" instead of using the ended job.
class SlotTurn {
 public:
  explicit SlotTurn(Slot& slot) : turn_(nullptr) {
    if (!slot.job) throwClosed();
    turn_.setJob(slot.job.get());
  }

 private:
  GlTurn turn_;
};

class PythonRenderer {
 public:
  explicit PythonRenderer(const py::kwargs& kwargs) {
    CLI::App app;
    cli::GlOptions options;
    cli::addGlOptions(app, options);
    parseKeywords(app, kwargs, "vsil.Renderer");
    context_ = cli::toContextOptions(options);
    GlTurn turn(nullptr);
    main_.job = std::make_unique<RenderJob>(context_);
    turn.setJob(main_.job.get());
  }

  ~PythonRenderer() { close(); }

  // Ends the contexts and frees the volumes' textures now; later calls raise ValueError.
  void close() {
    if (!main_.job) return;
    std::vector<std::shared_ptr<Slot>> resident;
    for (auto& [volume, slot] : resident_) resident.push_back(std::move(slot));
    resident_.clear();
    for (auto& slot : resident) release(slot);
    GlTurn turn(nullptr);  // the job's destructor makes its context current to delete objects
    main_ = Slot{};
  }

  bool closed() const { return !main_.job; }

  // What `--meta-out` writes under "gl": backend, platform, renderer, version, ...
  // Read in a turn: close() from another thread ends the job in a turn of its own.
  py::object glInfo() {
    nlohmann::ordered_json info;
    {
      SlotTurn turn(main_);
      info = gl::contextInfoJson(main_.job->context().info());
    }
    return jsonToPython(info);
  }

  // Uploads `volume` now (render does it when the volume changes; call this after changing a
  // volume's samples in place), in bricks of the last render's max_texture_mib; into its own
  // textures when it is resident.
  void upload(const PyVolume& volume) {
    job();
    std::shared_ptr<Slot> resident = residentSlot(volume.volume);
    Slot& slot = resident ? *resident : main_;
    {
      SlotTurn turn(slot);
      uploadInBricks(slot, volume.volume, slot.uploadedTextureBytes);
    }
    release(resident);
  }

  // Keeps `volume` resident: its own context and textures (one upload now), used by every
  // render of it until remove_volume, so that switching between resident volumes uploads
  // nothing. The main context serves every other volume, replacing its texture on each switch.
  void addVolume(const PyVolume& volume, std::optional<int> maxTextureMib) {
    job();
    if (resident_.count(volume.volume)) return;
    if (maxTextureMib && !(*maxTextureMib >= 1)) {
      throw InputError("vsil.Renderer.add_volume: max_texture_mib must be 1 or more");
    }
    const std::uint64_t textureBytes =
        maxTextureMib ? std::uint64_t(*maxTextureMib) << 20 : limits::kMaxTextureBytes;
    auto slot = std::make_shared<Slot>();
    {
      GlTurn turn(nullptr);
      slot->job = std::make_unique<RenderJob>(context_);
      turn.setJob(slot->job.get());
      uploadInBricks(*slot, volume.volume, textureBytes);
    }
    resident_.emplace(volume.volume, std::move(slot));  // with the GIL, as every reader
  }

  void removeVolume(const PyVolume& volume) {
    job();
    const auto it = resident_.find(volume.volume);
    if (it == resident_.end()) {
      throw InputError("vsil.Renderer.remove_volume: the volume is not resident (add_volume)");
    }
    std::shared_ptr<Slot> slot = std::move(it->second);
    resident_.erase(it);
    release(slot);
  }

  std::size_t residentCount() const { return resident_.size(); }
  std::uint64_t uploads() const { return uploads_; }

  Frame render(const py::object& input, const py::kwargs& kwargs) {
    const Request request = prepare(input, kwargs, "vsil.Renderer.render");
    std::shared_ptr<Slot> resident = request.volume ? residentSlot(request.volume) : nullptr;
    Slot& slot = resident ? *resident : main_;
    RenderOutput output;
    Held held;
    {
      // Upload (or load) and render in one turn: another thread's turn in between could
      // replace the volume this Renderer holds.
      SlotTurn turn(slot);
      held = holdVolume(slot, request);
      output = slot.job->render(request.render, request.load.limits);
    }
    Frame frame = makeFrame(output, request.render, held);
    release(resident);
    return frame;
  }

  // `vsil animate`'s frames (job/animation.h's AnimationPlan, the same code path): an orbit,
  // a view moving from view_from to view_to, sweeps {"iso": (0.3, 0.6)} or ["iso=0.3:0.6"];
  // a video file as --video writes it (video/video_file.h); the frames as Frames (keep_frames).
  py::list animate(const py::object& input, long long frames, double orbit,
                   const py::object& viewFrom, const py::object& viewTo, const py::object& sweep,
                   const py::object& video, double fps, bool keepFrames, const py::kwargs& kwargs) {
    const std::string function = "vsil.Renderer.animate";
    Request request = prepare(input, kwargs, function);
    request.render.settings.readDepth = false;  // as vsil animate: frames are images only
    AnimationSpec spec;
    spec.frames = frames;
    spec.orbitDeg = orbit;
    const Keyword pair = textKeyword("view_from");
    if (viewFrom.is_none() != viewTo.is_none()) {
      throw InputError(function + ": give view_from and view_to together");
    }
    if (!viewFrom.is_none()) {
      spec.viewFrom = parseNumberPair("--view-from", valueText(pair, viewFrom, function));
      spec.viewTo = parseNumberPair("--view-to", valueText(pair, viewTo, function));
    }
    // As vsil animate: a keyword the frames set would be lost (the CLI refuses both).
    const auto given = [&](const std::string& key) {
      return kwargs.contains(key.c_str()) && !kwargs[key.c_str()].is_none();
    };
    if (!viewFrom.is_none() && given("view")) {
      throw InputError(function +
                       ": view= is given too, and view_from/view_to set the view of "
                       "every frame: give one of them");
    }
    for (const std::string& text : sweepTexts(sweep, function)) {
      spec.sweeps.push_back(parseSweep(text));
      std::string key = spec.sweeps.back().name;
      std::replace(key.begin(), key.end(), '-', '_');
      if (given(key)) {
        throw InputError(function + ": sweep " + text + ": " + key +
                         "= is given too, and the sweep sets it on every frame: give one of them");
      }
    }
    const AnimationPlan plan(request.render, spec, request.load.limits);
    std::string videoPath;
    if (!video.is_none()) {
      videoPath = valueText(textKeyword("video"), video, function);
      VideoFile::checkTarget("--video", videoPath, request.render.settings.size, fps);
    } else if (!VideoFile::validFps(fps)) {
      throw InputError(function + ": fps " + formatNumber(fps) + " must be in " +
                       VideoFile::kFpsRange);
    } else if (!keepFrames) {
      throw InputError(function + ": keep_frames=False without video= keeps nothing of the " +
                       "frames: give video=, or keep the frames");
    }
    std::shared_ptr<Slot> resident = request.volume ? residentSlot(request.volume) : nullptr;
    Slot& slot = resident ? *resident : main_;
    std::vector<RenderOutput> outputs;
    Held held;
    AnimationWarnings warnings;
    std::vector<std::string> said;
    {
      SlotTurn turn(slot);
      held = holdVolume(slot, request);
      std::optional<VideoFile> file;
      if (!videoPath.empty()) file.emplace(videoPath, request.render.settings.size, fps);
      for (int i = 0; i < plan.frames(); ++i) {
        {
          // Ctrl-C (and any signal handler's exception) between frames, as the CLI stops at
          // the signal: the video's temporary is removed, no frames are returned.
          const py::gil_scoped_acquire acquire;
          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        }
        RenderOutput output = slot.job->render(plan.request(i), request.load.limits);
        if (file) file->write(output.image);
        output.metadata["swept"] = plan.sweptValues(i);
        for (std::string& warning : warnings.add(output.warnings)) said.push_back(warning);
        if (keepFrames) outputs.push_back(std::move(output));
      }
      if (file) file->finish();
    }
    for (std::string& warning : warnings.finish(plan.frames())) said.push_back(warning);
    py::list result;
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      result.append(makeFrame(outputs[i], plan.request(int(i)), i == 0 ? held : Held{},
                              /*warn=*/false));
    }
    for (const std::string& warning : said) warnUser("vsil: " + warning);
    release(resident);
    return result;
  }

 private:
  // A render's request as the flags give it, and what it renders.
  struct Request {
    RenderRequest render;
    LoadOptions load;
    std::string spec;                // a path or gen: spec read in the turn, or ""
    std::shared_ptr<Volume> volume;  // a Volume, or null
  };
  // What holding the volume took and what it is, for the metadata.
  struct Held {
    nlohmann::json dataset = nlohmann::json::object();  // read, file (as --meta-out)
    StageTime read, upload;
  };

  Request prepare(const py::object& input, const py::kwargs& kwargs, const std::string& function) {
    job();
    // Flags that choose what render does not own here: the context is the Renderer's, and a
    // Volume is read already.
    const bool isPath = py::isinstance<py::str>(input);
    for (const char* key : {"gl", "gl_device"}) {
      if (kwargs.contains(key)) {
        throw InputError(function + ": " + std::string(key) +
                         " is chosen when the Renderer is made: vsil.Renderer(" + key + "=...)");
      }
    }
    for (const char* key : {"dims", "type", "spacing", "endian", "crop", "stride", "series"}) {
      if (!isPath && kwargs.contains(key)) {
        throw InputError(function + ": " + std::string(key) +
                         " applies when a file is read: vsil.load(path, " + key + "=...)");
      }
    }
    CLI::App app;
    cli::RenderFlags flags;
    cli::addRenderOptions(app, flags);
    parseKeywords(app, kwargs, function);
    Request request;
    request.render = cli::toRenderRequest(flags);
    request.load = cli::toLoadOptions(flags.volume);
    RenderJob::checkRequest(request.render, request.load.limits);
    if (!isPath && !py::isinstance<PyVolume>(input)) {
      throw PythonTypeError(function +
                            ": volume must be a vsil.Volume, a path or a gen: spec, "
                            "not " +
                            typeNameOf(input));
    }
    if (isPath) {
      request.spec = fsBytes(input);
    } else {
      request.volume = input.cast<const PyVolume&>().volume;
    }
    return request;
  }

  // During a turn: reads the path (on every call: the file may have changed; a sweep loads
  // once with vsil.load) or uploads the Volume unless the slot's texture holds it.
  Held holdVolume(Slot& slot, const Request& request) {
    Held held;
    RenderJob& job = *slot.job;
    StageClock clock;
    const std::uint64_t textureBytes = request.load.limits.maxTextureBytes;
    if (!request.spec.empty()) {
      Volume loaded = loadOrNotFound(
          [&] {
            return loadVolume(request.spec,
                              RenderJob::loadOptionsFor(request.render, request.load));
          },
          request.spec);
      held.read = clock.lap();
      job.setVolume(std::move(loaded), request.spec, textureBytes);
      held.upload = clock.lap();
      ++uploads_;
      slot.uploaded.reset();
    } else if (request.volume != slot.uploaded || textureBytes != slot.uploadedTextureBytes) {
      uploadInBricks(slot, request.volume, textureBytes);
      held.upload = clock.lap();
    }
    if (auto read = cli::describeRead<nlohmann::json>(job.volume()); !read.is_null()) {
      held.dataset["read"] = read;
    }
    if (auto file = cli::describeFile<nlohmann::json>(job.volume()); !file.is_null()) {
      held.dataset["file"] = file;
    }
    return held;
  }

  // The Frame of an output, with the GIL: the metadata as --meta-out writes it.
  // `warn`: issue the frame's warnings as Python warnings (animate says its frames' once).
  static Frame makeFrame(RenderOutput& output, const RenderRequest& request, const Held& held,
                         bool warn = true) {
    nlohmann::json& meta = output.metadata;
    for (const auto& [key, value] : held.dataset.items()) meta["dataset"][key] = value;
    // The stages of this call before the frame's own (0 where the texture was resident).
    meta["timings_ms"]["read"] = held.read.wallMs;
    meta["cpu_ms"]["read"] = held.read.cpuMs;
    meta["timings_ms"]["upload"] = held.upload.wallMs;
    meta["cpu_ms"]["upload"] = held.upload.cpuMs;
    cv::Mat rgba;
    cv::cvtColor(output.image, rgba,
                 output.image.channels() == 4 ? cv::COLOR_BGRA2RGBA : cv::COLOR_BGR2RGBA);
    // None for what the technique does not make (mip's states), as --state-out refuses it.
    const FrameOutputs& makes = findTechnique(request.settings.technique).outputs;
    const FrameBuffers& buffers = output.result.frame;
    Frame frame;
    frame.image = arrayFromMat<std::uint8_t>(rgba, 4);
    frame.state = makes.state && !buffers.state.empty()
                      ? py::object(arrayFromMat<std::uint8_t>(buffers.state, 1))
                      : py::none();
    frame.depth = makes.depth && !buffers.depth.empty()
                      ? py::object(arrayFromMat<float>(buffers.depth, 1))
                      : py::none();
    frame.metadata = jsonToPython(meta);
    frame.warnings = output.warnings;
    if (warn) {
      for (const std::string& warning : output.warnings) warnUser("vsil: " + warning);
    }
    return frame;
  }

  // sweep={"iso": (0.3, 0.6), "cursor": ((0, 0, 0), (9, 9, 9))} or ["iso=0.3:0.6", ...]: the
  // texts --sweep takes.
  static std::vector<std::string> sweepTexts(const py::object& sweep, const std::string& function) {
    std::vector<std::string> texts;
    if (sweep.is_none()) return texts;
    if (py::isinstance<py::str>(sweep)) return {sweep.cast<std::string>()};
    if (py::isinstance<py::dict>(sweep)) {
      const Keyword ends = textKeyword("sweep");
      for (const auto& [name, range] : py::reinterpret_borrow<py::dict>(sweep)) {
        if (!isSequence(range) || py::len(range) != 2) {
          throw PythonTypeError(function + ": sweep takes {name: (from, to)}, not " +
                                typeNameOf(range) + " for " + std::string(py::str(name)));
        }
        const py::sequence pair = py::reinterpret_borrow<py::sequence>(range);
        texts.push_back(std::string(py::str(name)) + "=" + valueText(ends, pair[0], function) +
                        ":" + valueText(ends, pair[1], function));
      }
      return texts;
    }
    if (isSequence(sweep)) {
      for (const py::handle item : sweep) {
        if (!py::isinstance<py::str>(item)) {
          throw PythonTypeError(function + ": sweep takes a dict or texts NAME=A:B, not " +
                                typeNameOf(item) + " items");
        }
        texts.push_back(item.cast<std::string>());
      }
      return texts;
    }
    throw PythonTypeError(function + ": sweep takes a dict or texts NAME=A:B, not " +
                          typeNameOf(sweep));
  }

  RenderJob& job() const {
    if (!main_.job) throwClosed();
    return *main_.job;
  }

  std::shared_ptr<Slot> residentSlot(const std::shared_ptr<Volume>& volume) const {
    const auto it = resident_.find(volume);
    return it == resident_.end() ? nullptr : it->second;
  }

  // Drops a reference to a resident slot (with the GIL); the last one ends its context in a turn.
  static void release(std::shared_ptr<Slot>& slot) {
    if (slot && slot.use_count() == 1) {
      GlTurn turn(nullptr);
      slot.reset();
    }
    slot.reset();
  }

  // During a turn (no GIL: the samples are read as raw memory).
  void uploadInBricks(Slot& slot, const std::shared_ptr<Volume>& volume,
                      std::uint64_t maxTextureBytes) {
    // Until the samples are in the textures: a refused upload (a NaN written in place) must not
    // leave the next render on the previous samples as if they were these.
    slot.uploaded.reset();
    requireFiniteSamples(*volume);
    slot.job->setVolume(Volume::sharing(volume), volume->source, maxTextureBytes);
    slot.uploaded = volume;
    slot.uploadedTextureBytes = maxTextureBytes;
    ++uploads_;
  }

  gl::ContextOptions context_;
  Slot main_;
  // Read and changed with the GIL held; a slot's job used during turns only.
  std::map<std::shared_ptr<Volume>, std::shared_ptr<Slot>> resident_;
  // Textures filled, for tests and users who count; written in turns (no GIL), read with it.
  std::atomic<std::uint64_t> uploads_ = 0;
};

// ---- postfx on arrays ----

// "a uint8 array of shape (64, 64, 4)": what a wrong array was, for a message.
std::string arrayText(const py::array& array) {
  return "a " + std::string(py::str(array.dtype())) + " array of shape " +
         std::string(py::str(py::tuple(
             py::cast(std::vector<py::ssize_t>(array.shape(), array.shape() + array.ndim())))));
}

cv::Mat1b maskFromArray(const py::array& lines, const std::string& function) {
  if (lines.ndim() != 2) {
    throw InputError(function + ": expected a 2-dimensional line mask (non-zero = line), not " +
                     arrayText(lines));
  }
  // The image side of a render (--size), checked before the array is copied or converted.
  if (lines.shape(0) < 1 || lines.shape(1) < 1 || lines.shape(0) > limits::kMaxImageSide ||
      lines.shape(1) > limits::kMaxImageSide) {
    throw InputError(function + ": a " + std::to_string(lines.shape(0)) + "x" +
                     std::to_string(lines.shape(1)) + " mask; each side must be 1 .. " +
                     std::to_string(limits::kMaxImageSide) + " pixels");
  }
  // Non-zero is a line, whatever the dtype (a cast to uint8 read 0.5 as 0); NaN is neither.
  const py::module_ np = py::module_::import("numpy");
  if (np.attr("issubdtype")(lines.dtype(), np.attr("inexact")).cast<bool>() &&
      np.attr("isnan")(lines).attr("any")().cast<bool>()) {
    throw InputError(function + ": the line mask holds NaN (non-zero = line, 0 = none)");
  }
  const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast> mask(
      np.attr("not_equal")(lines, 0));
  cv::Mat1b result(int(mask.shape(0)), int(mask.shape(1)));
  std::memcpy(result.data, mask.data(), result.total());
  return result;
}

// Normalized depths as Frame.depth holds them: floats in [0, 1], NaN where a pixel has none.
// Another dtype (a depth image's uint16 codes) or a value outside [0, 1] is refused: it would
// land in the first or last bin.
cv::Mat1f depthFromArray(const py::array& depth, cv::Size size, const std::string& function) {
  const py::module_ np = py::module_::import("numpy");
  if (!np.attr("issubdtype")(depth.dtype(), np.attr("floating")).cast<bool>()) {
    throw PythonTypeError(function + ": depth must be floats in [0, 1] (NaN: none), not " +
                          std::string(py::str(depth.dtype())));
  }
  const py::array_t<float, py::array::c_style | py::array::forcecast> values(depth);
  if (values.ndim() != 2 || values.shape(0) != size.height || values.shape(1) != size.width) {
    throw InputError(function + ": depth must be a 2-dimensional array of the image's shape");
  }
  cv::Mat1f result(size);
  std::memcpy(result.data, values.data(), result.total() * sizeof(float));
  for (int y = 0; y < result.rows; ++y) {
    for (int x = 0; x < result.cols; ++x) {
      const float d = result(y, x);
      if (!std::isnan(d) && !(d >= 0.0f && d <= 1.0f)) {
        throw InputError(function + ": depth[" + std::to_string(y) + ", " + std::to_string(x) +
                         "] is " + formatNumber(d) + ": depths are in [0, 1] (NaN: none)");
      }
    }
  }
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
    if (widthNear || widthFar || depth) {
      throw InputError(function + ": give width, or width_near, width_far and depth, not both");
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
    throw InputError(function + ": expected a 2-dimensional line mask (non-zero = line), not " +
                     arrayText(image));
  }
  if (!(bins >= 1 && bins <= 1000)) throw InputError(function + ": bins must be in 1 .. 1000");
  checkHistogramBinWidth(function + ": bin_width", binWidth);
  const cv::Mat1b mask = maskFromArray(image, function);
  const auto samples = measureLineWidths(mask, function, limits::defaultMemoryBytes());
  // Issued as UserWarning and kept in the report, as --json keeps them.
  std::vector<std::string> warnings;
  if (std::string warning = regionsNotLinesWarning(mask, samples, function); !warning.empty()) {
    warnings.push_back(std::move(warning));
  }
  std::vector<double> widths;
  for (const auto& s : samples) widths.push_back(s.width);
  nlohmann::json report = {{"widths", widthStatisticsJson(summarizeWidths(widths, binWidth))}};
  if (depth) {
    const cv::Mat1f depths = depthFromArray(*depth, mask.size(), function);
    const auto byDepth = widthAgainstDepth(samples, depths, bins);
    if (std::string warning = emptyDepthBinsWarning(samples, byDepth, function + ": depth");
        !warning.empty()) {
      warnings.push_back(std::move(warning));
    }
    report["by_depth"] = depthBinsJson(byDepth);
  }
  report["warnings"] = warnings;
  for (const std::string& warning : warnings) warnUser(warning);
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

// The extension vsil._vsil; the package vsil (vsil/__init__.py) is what users import.
PYBIND11_MODULE(_vsil, m) {
  using namespace vsil;
  using namespace vsil::python;
  m.doc() = "vsil: volume illustration (exact silhouettes, Ebert-Rheingans, DEMIP) offscreen";
  // The top-level project() version (core/version.h), as the package metadata has it (setup.py).
  m.attr("__version__") = kVsilVersion;

  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const PythonTypeError& e) {
      PyErr_SetObject(PyExc_TypeError, fsText(e.what()).ptr());
    } catch (const VolumeNotFound& e) {
      // FileNotFoundError(errno, strerror, filename): e.filename is the path, str(e) holds the
      // CLI's one-line message.
      const py::object error = py::reinterpret_borrow<py::object>(PyExc_FileNotFoundError)(
          ENOENT, fsText(e.what()), fsText(e.path));
      PyErr_SetObject(PyExc_FileNotFoundError, error.ptr());
    } catch (const InputError& e) {
      PyErr_SetObject(PyExc_ValueError, fsText(e.what()).ptr());
    } catch (const UnavailableError& e) {
      PyErr_SetObject(PyExc_RuntimeError, fsText(e.what()).ptr());
    }
  });

  py::class_<PyVolume>(m, "Volume", "A scalar volume; .data is a numpy view (z, y, x)")
      .def(py::init(&makeVolume), py::arg("array"),
           py::arg("spacing") = py::make_tuple(1.0, 1.0, 1.0), py::arg("name") = "array",
           "Wraps a C-contiguous (z, y, x) array of uint8, int8, uint16, int16 or float32 "
           "without copying; other real or boolean dtypes, other strides and big-endian "
           "arrays are copied once (a UserWarning says why); spacing is (x, y, z)")
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
      // Names as os.fsdecode gives them (a file name need not be UTF-8: round 15).
      .def_property_readonly("name", [](const PyVolume& v) { return fsText(v.volume->name); })
      .def_property_readonly("source", [](const PyVolume& v) { return fsText(v.volume->source); })
      .def_property_readonly(
          "format", [](const PyVolume& v) { return fsText(v.volume->format); },
          "the file's format and variant, '' for generated volumes")
      .def_property_readonly(
          "warnings",
          [](const PyVolume& v) {
            py::list warnings;
            for (const std::string& warning : v.volume->warnings) warnings.append(fsText(warning));
            return warnings;
          },
          "what reading the file warned about (also issued as UserWarning)")
      .def_property_readonly("dtype", [](const PyVolume& v) { return dtypeOf(v.volume->type()); })
      .def_property_readonly("value_range",
                             [](const PyVolume& v) {
                               const ValueRange range = valueRange(*v.volume);
                               return py::make_tuple(range.min, range.max);
                             })
      .def("__repr__", [](const PyVolume& v) {
        const Volume& volume = *v.volume;
        return fsText("<vsil.Volume " + volume.name + " " + std::to_string(volume.dims.x) + "x" +
                      std::to_string(volume.dims.y) + "x" + std::to_string(volume.dims.z) + " " +
                      sampleTypeName(volume.type()) + ">");
      });

  m.def("load", &load, py::arg("path"),
        "Reads a volume file or generates a gen: volume; keywords: the volume flags of "
        "`vsil render` (dims, type, spacing, endian, crop, stride, max_memory)");
  m.def("info", &info, py::arg("volume"),
        "What `vsil info VOLUME --json` prints, as a dict: a file or gen: spec read with the "
        "volume keywords, or a Volume");
  m.def(
      "generate",
      [](const std::string& name, int size) {
        return load(py::str("gen:" + name + ":" + std::to_string(size)), py::kwargs());
      },
      py::arg("name"), py::arg("size") = 128, "A procedural volume, as INPUT gen:NAME:SIZE");

  py::class_<Frame>(m, "Frame", "One rendered frame")
      .def_readonly("image", &Frame::image, "H x W x 4 uint8, RGBA")
      .def_readonly("state", &Frame::state,
                    "H x W uint8 pixel states; None for techniques that make none (mip, ...)")
      .def_readonly("depth", &Frame::depth,
                    "H x W float32 normalized depth, NaN where none; None for techniques that "
                    "make no depth. For silhouette and rightangle every first hit's depth, "
                    "Filled pixels too; `vsil render --depth-out` keeps the line pixels' only "
                    "(where state == 3)")
      .def_readonly("metadata", &Frame::metadata,
                    "what `vsil render --meta-out` writes, less parameters.out; timings_ms and "
                    "cpu_ms hold this call's read, upload (0: the texture was resident) and the "
                    "frame's stages")
      .def_property_readonly("warnings",
                             [](const Frame& frame) {
                               py::list texts;
                               for (const auto& warning : frame.warnings)
                                 texts.append(fsText(warning));
                               return texts;
                             })
      .def("__repr__",
           [](const Frame& frame) {
             const py::object technique = frame.metadata["parameters"]["technique"];
             return "<vsil.Frame " + std::to_string(frame.image.shape(1)) + "x" +
                    std::to_string(frame.image.shape(0)) + " " + std::string(py::str(technique)) +
                    ">";
           })
      .def(
          "_repr_png_",
          [](const Frame& frame) {
            // The image as PNG, for notebooks (IPython's display protocol).
            const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast> rgba(
                frame.image);
            const cv::Mat view(int(rgba.shape(0)), int(rgba.shape(1)), CV_8UC4,
                               const_cast<std::uint8_t*>(rgba.data()));
            cv::Mat bgra;
            cv::cvtColor(view, bgra, cv::COLOR_RGBA2BGRA);
            const std::vector<std::uint8_t> png = encodePng(bgra);
            return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
          },
          "The image as PNG bytes (how Jupyter shows a Frame)");

  // The base of vsil.Renderer (vsil/__init__.py adds signatures and os.PathLike inputs).
  py::class_<PythonRenderer>(m, "_Renderer",
                             "One GL context; keywords gl, gl_device as `vsil render`")
      .def(py::init<const py::kwargs&>())
      .def("close", &PythonRenderer::close,
           "Ends the GL context and frees the textures now (also at the end of a with block)")
      .def_property_readonly("closed", &PythonRenderer::closed)
      .def("__repr__",
           [](PythonRenderer& renderer) {
             if (renderer.closed()) return std::string("<vsil.Renderer closed>");
             const py::dict gl = renderer.glInfo();
             return "<vsil.Renderer " + std::string(py::str(gl["backend"])) + ", " +
                    std::string(py::str(gl["renderer"])) + ">";
           })
      .def("__enter__",
           [](const py::object& self) {
             // As a closed file does: a with block on a closed Renderer would fail inside.
             if (self.cast<PythonRenderer&>().closed()) throwClosed();
             return self;
           })
      .def("__exit__", [](PythonRenderer& renderer, const py::args&) { renderer.close(); })
      .def_property_readonly("gl", &PythonRenderer::glInfo,
                             "The GL context: backend, platform, renderer, version, ...")
      .def("render", &PythonRenderer::render, py::arg("volume"),
           "Renders a Volume (or a path or gen: spec); keywords: every flag of `vsil render` "
           "by its name with _ for - (iso=40, width_near=4, view=(30, 20), size=(640, 480))")
      .def("animate", &PythonRenderer::animate, py::arg("volume"), py::kw_only(), py::arg("frames"),
           py::arg("orbit") = 0.0, py::arg("view_from") = py::none(),
           py::arg("view_to") = py::none(), py::arg("sweep") = py::none(),
           py::arg("video") = py::none(), py::arg("fps") = 25.0, py::arg("keep_frames") = true,
           "vsil animate's frames in one turn: orbit degrees over the sequence, view_from/"
           "view_to, sweep={name: (from, to)}; video= writes the file as --video does; returns "
           "the Frames (none with keep_frames=False)")
      .def("upload", &PythonRenderer::upload, py::arg("volume"),
           "Uploads the volume again (after its samples changed in place)")
      .def("add_volume", &PythonRenderer::addVolume, py::arg("volume"),
           py::arg("max_texture_mib") = py::none(),
           "Keeps the volume resident (its own textures, uploaded once now) until "
           "remove_volume: renders switching between resident volumes upload nothing")
      .def("remove_volume", &PythonRenderer::removeVolume, py::arg("volume"),
           "Frees a resident volume's textures")
      .def_property_readonly("resident_volumes", &PythonRenderer::residentCount,
                             "How many volumes add_volume keeps resident")
      .def_property_readonly("uploads", &PythonRenderer::uploads,
                             "How many times this Renderer filled textures with a volume");

  m.def("_keywords", &keywordTable, py::arg("function"),
        "The keywords of render, load or Renderer, from the CLI's option tables: key, flag, "
        "kind, help, group, default, choices, number_count");
  for (const char* name : {"Volume", "Frame"}) m.attr(name).attr("__module__") = "vsil";

  m.def("broaden", &broaden, py::arg("lines"), py::kw_only(), py::arg("width") = py::none(),
        py::arg("width_near") = py::none(), py::arg("width_far") = py::none(),
        py::arg("depth") = py::none(),
        "Broadens one-pixel lines (non-zero pixels) to `width`, or from width_near to "
        "width_far by `depth` (normalized, NaN where none); returns a 0/255 uint8 mask");
  m.def("measure_width", &measureWidth, py::arg("lines"), py::kw_only(),
        py::arg("depth") = py::none(), py::arg("bins") = 10, py::arg("bin_width") = 1.0,
        "Line widths of a mask (non-zero = line) on its medial axis: the statistics "
        "`vsil measure-width --json` writes, by_depth with `depth` (floats in [0, 1], NaN: none; "
        "an empty bin's widths are None), and samples (x, y, width)");
}
