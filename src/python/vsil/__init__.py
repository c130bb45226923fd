"""vsil: volume illustration (exact silhouettes, Ebert-Rheingans, fuzzy-rule semantics,
depth-enhanced MIP) rendered offscreen with OpenGL, in one process, on numpy arrays.

    import vsil
    volume = vsil.load("bonsai.vti")            # or vsil.Volume(ndarray), vsil.generate(...)
    with vsil.Renderer() as renderer:           # one GL context, reused by every render
        frame = renderer.render(volume, iso=40, width_near=4, width_far=1)
    frame.image, frame.state, frame.depth, frame.metadata

The keywords of Renderer, Renderer.render and load are the flags of `vsil render` with _ for -;
their signatures, help and the stub (__init__.pyi) are made from the CLI's option tables
(vsil._vsil._keywords), so they list what the command line takes, with its defaults.
"""
import functools
import inspect
import numbers
import os
import re

from . import _vsil
from ._vsil import Frame, Volume, __version__

__all__ = ["Frame", "Renderer", "Volume", "__version__", "broaden", "generate", "info", "load",
           "measure_width"]

# The keyword kinds' types, by the names the stub defines (__init__.pyi: Number, Text, Texts).
_ANNOTATIONS = {"switch": "bool", "number": "Number", "integer": "int", "text": "Text",
                "list": "Texts"}


def _annotation(keyword):
    """The keyword's type as the stub writes it (a string: nothing is imported for it)."""
    if keyword["kind"] == "choice":
        annotation = "Literal[" + ", ".join(repr(c) for c in keyword["choices"]) + "]"
    else:
        annotation = _ANNOTATIONS[keyword["kind"]]
    return annotation if keyword["default"] is not None else annotation + " | None"


def _parameters(function):
    return [inspect.Parameter(k["key"], inspect.Parameter.KEYWORD_ONLY, default=k["default"],
                              annotation=_annotation(k))
            for k in _vsil._keywords(function)]


def _keyword_help(function):
    """One line per keyword: name = default, then the CLI's help for the flag."""
    lines = []
    group = None
    for k in _vsil._keywords(function):
        if k["group"] != group:
            group = k["group"]
            lines += ["", f"{group}:"]
        choices = " | ".join(k["choices"])
        choices = f" ({choices})" if choices and choices not in k["help"] else ""
        lines.append(f"    {k['key']}={k['default']!r}{choices}: {k['help']}")
    return "\n".join(lines)


def _fspath(value):
    return os.fspath(value) if isinstance(value, os.PathLike) else value


def _signed(function, parameters, doc):
    function.__signature__ = inspect.Signature(parameters)
    function.__doc__ = doc
    return function


class Renderer(_vsil._Renderer):
    """One GL context (OSMesa or EGL, as `vsil render --gl`), reused by every render; any thread
    may use it (GL work takes turns under one lock). A context manager: `with vsil.Renderer() as
    r:` ends the context at the end of the block (also r.close()). add_volume(v) keeps a volume
    resident (its own textures): renders switching between resident volumes upload nothing."""

    def __init__(self, **options):
        super().__init__(**options)

    def render(self, volume, **options):
        return super().render(_fspath(volume), **options)

    def animate(self, volume, *, frames, orbit=0.0, view_from=None, view_to=None, sweep=None,
                video=None, fps=25.0, keep_frames=True, **options):
        # One line naming the argument (pybind11's TypeError lists the whole signature).
        def wrong(name, takes, value):
            raise TypeError(f"vsil.Renderer.animate: {name} takes {takes}, not "
                            f"{type(value).__name__}")
        if isinstance(frames, bool) or not isinstance(frames, numbers.Integral):
            wrong("frames", "an int", frames)
        for name, value in (("orbit", orbit), ("fps", fps)):
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                wrong(name, "a number", value)
        if not isinstance(keep_frames, bool):
            wrong("keep_frames", "True or False", keep_frames)
        return super().animate(_fspath(volume), frames=frames, orbit=orbit, view_from=view_from,
                               view_to=view_to, sweep=sweep, video=_fspath(video), fps=fps,
                               keep_frames=keep_frames, **options)

    def upload(self, volume):
        """Uploads the volume again (after its samples changed in place)."""
        _require_volume("vsil.Renderer.upload", volume)
        return super().upload(volume)

    def add_volume(self, volume, max_texture_mib=None):
        """Keeps the volume resident (its own textures, uploaded once now) until remove_volume:
        renders switching between resident volumes upload nothing."""
        _require_volume("vsil.Renderer.add_volume", volume)
        if max_texture_mib is not None and (isinstance(max_texture_mib, bool)
                                            or not isinstance(max_texture_mib, numbers.Integral)):
            raise TypeError("vsil.Renderer.add_volume: max_texture_mib takes an int, not "
                            f"{type(max_texture_mib).__name__}")
        return super().add_volume(volume, max_texture_mib)


def _require_volume(function, volume):
    """One line naming the argument (pybind11's TypeError lists the whole signature)."""
    if not isinstance(volume, Volume):
        raise TypeError(f"{function}: volume takes a vsil.Volume, not {type(volume).__name__}")


_SELF = inspect.Parameter("self", inspect.Parameter.POSITIONAL_OR_KEYWORD)
_signed(Renderer.__init__, [_SELF] + _parameters("Renderer"),
        "gl: the back end (default $VSIL_GL, else auto); gl_device: the EGL device.\n"
        + _keyword_help("Renderer"))
_signed(Renderer.render,
        [_SELF, inspect.Parameter("volume", inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                  annotation="Volume | str | os.PathLike[str]")]
        + _parameters("render"),
        "Renders a Volume (or a path or gen: spec, read at each call with the volume keywords)\n"
        "into a Frame: the pixels `vsil render` writes with the same flags, byte for byte.\n"
        "A keyword left at None takes the command line's default (the help says which);\n"
        "sequences join as the flags write them: size=(640, 480), view=(30, 20).\n"
        + _keyword_help("render"))


_ANIMATION = [
    inspect.Parameter("frames", inspect.Parameter.KEYWORD_ONLY, annotation="int"),
    inspect.Parameter("orbit", inspect.Parameter.KEYWORD_ONLY, default=0.0, annotation="float"),
    inspect.Parameter("view_from", inspect.Parameter.KEYWORD_ONLY, default=None,
                      annotation="Text | None"),
    inspect.Parameter("view_to", inspect.Parameter.KEYWORD_ONLY, default=None,
                      annotation="Text | None"),
    inspect.Parameter("sweep", inspect.Parameter.KEYWORD_ONLY, default=None,
                      annotation="dict[str, Sequence[Any]] | Sequence[str] | str | None"),
    inspect.Parameter("video", inspect.Parameter.KEYWORD_ONLY, default=None,
                      annotation="str | os.PathLike[str] | None"),
    inspect.Parameter("fps", inspect.Parameter.KEYWORD_ONLY, default=25.0, annotation="float"),
    inspect.Parameter("keep_frames", inspect.Parameter.KEYWORD_ONLY, default=True,
                      annotation="bool"),
]
_signed(Renderer.animate,
        [_SELF, inspect.Parameter("volume", inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                  annotation="Volume | str | os.PathLike[str]")]
        + _ANIMATION + _parameters("render"),
        "`vsil animate` in one call, on the same code path (job/animation.h, video_file.h):\n"
        "frames; orbit degrees of azimuth over the sequence (frame i adds orbit*i/frames);\n"
        "view_from/view_to (AZ, EL) moving linearly; sweep={'iso': (0.3, 0.6)} (or texts\n"
        "'iso=0.3:0.6'); video= a .mp4 or .avi file written as --video writes it, at fps.\n"
        "Returns the list of Frames (each metadata['swept'] says its values; [] with\n"
        "keep_frames=False). The render keywords as Renderer.render.\n"
        + _keyword_help("render"))


def load(path, **options):
    return _vsil.load(_fspath(path), **options)


_signed(load, [inspect.Parameter("path", inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                 annotation="str | os.PathLike[str]")] + _parameters("load"),
        "Reads a volume file (or generates a gen:NAME[:N] volume) as `vsil render` reads INPUT.\n"
        "FileNotFoundError for a path that is not there, ValueError for a bad file.\n"
        + _keyword_help("load"))


def info(volume, **options):
    return _vsil.info(_fspath(volume), **options)


_signed(info, [inspect.Parameter("volume", inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                 annotation="Volume | str | os.PathLike[str]")]
        + _parameters("load"),
        "What `vsil info VOLUME --json` prints, as a dict (dims, type, spacing, min, max, mean,\n"
        "stddev, default_iso, percentiles, histogram, ...): for a file or gen: spec read with\n"
        "the volume keywords (as load), or for a Volume.\n" + _keyword_help("load"))


def generate(name, size=128):
    """A procedural volume, as INPUT gen:NAME:SIZE."""
    # One line naming the argument; a bool is no size (pybind11 takes True as 1).
    if not isinstance(name, str):
        raise TypeError(f"vsil.generate: name takes a str, not {type(name).__name__}")
    if isinstance(size, bool) or not isinstance(size, numbers.Integral):
        raise TypeError(f"vsil.generate: size takes an int, not {type(size).__name__}")
    return _vsil.generate(name, size)


def _argument_text(value):
    """What a wrong argument was, short: an array by its dtype and shape, not its elements (as
    the module's own messages say it)."""
    if hasattr(value, "dtype") and hasattr(value, "shape"):
        return f"a {value.dtype} array of shape {tuple(value.shape)}"
    text = repr(value)
    return f"{type(value).__name__} {text[:40] + '...' if len(text) > 40 else text}"


def _one_line_type_errors(function, name):
    """pybind11's TypeError for arguments of the wrong types spans several lines (the supported
    signatures, a blank line, what it was given, arrays element by element): one line naming
    the function, the keyword it does not know or the arguments' types instead. Their keywords
    take numbers and arrays: a bool is refused."""
    @functools.wraps(function)
    def call(*args, **kwargs):
        for key, value in kwargs.items():  # pybind11 takes True as the number 1
            if isinstance(value, bool):
                raise TypeError(f"vsil.{name}: {key} takes a number, not bool")
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            text = str(error)
            lines = [line.strip() for line in text.splitlines() if line.strip()]
            if not lines or "incompatible function arguments" not in lines[0]:
                raise
            takes = lines[1].split(". ", 1)[-1].rsplit(" -> ", 1)[0] if len(lines) > 1 else "?"
            known = re.findall(r"(\w+):", takes)
            unknown = [key for key in kwargs if key not in known]
            if unknown:
                raise TypeError(f"vsil.{name}: unknown keyword '{unknown[0]}' (it takes "
                                f"{', '.join(known)})") from None
            given = [_argument_text(value) for value in args]
            given += [f"{key}={_argument_text(value)}" for key, value in kwargs.items()]
            raise TypeError(f"vsil.{name}: takes {takes}, not ({', '.join(given)})") from None
    return call


broaden = _one_line_type_errors(_vsil.broaden, "broaden")
measure_width = _one_line_type_errors(_vsil.measure_width, "measure_width")

