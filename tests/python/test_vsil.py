"""The Python module against the command line, and on its own: round trips to the CLI's bytes,
zero-copy wrapping, exceptions, a parameter sweep in one process, postfx on arrays.

Run by ctest (tests/CMakeLists.txt) with PYTHONPATH=build/python and VSIL_BINARY set, and by
scripts/test-python-package.sh against the package pip installed into a venv
(VSIL_TEST_INSTALLED names it)."""

import errno
import inspect
import io
import json
import os
import pathlib
import re
import subprocess
import sys
import warnings

import numpy as np
import pytest
from PIL import Image

import vsil

VSIL = os.environ.get("VSIL_BINARY", "vsil")


def run_cli(*args):
    return subprocess.run([VSIL, *args], capture_output=True, text=True, check=True)


@pytest.fixture(scope="module")
def renderer():
    return vsil.Renderer()


def decode_depth(path):
    """render --depth-out: 0 = none, else 1 + round(d * 65534) (core/depth_image.h)."""
    raw = np.asarray(Image.open(path)).astype(np.float64)
    return np.where(raw == 0, np.nan, (raw - 1) / 65534)


# ---- the package ----

def test_the_package_is_the_one_asked_for_and_has_the_project_version():
    # scripts/test-python-package.sh: the copy pip installed into that venv, not the build tree.
    installed = os.environ.get("VSIL_TEST_INSTALLED")
    if installed:
        assert os.path.realpath(vsil.__file__).startswith(os.path.realpath(installed) + os.sep)
    cmake = open(os.path.join(os.path.dirname(__file__), "..", "..", "CMakeLists.txt")).read()
    assert re.search(r"project\(vsil VERSION ([0-9.]+)", cmake).group(1) == vsil.__version__
    assert vsil.__version__ in run_cli("--version").stdout
    # Renderer.animate(video=...) loads the video plugin the package carries beside the extension.
    assert (pathlib.Path(vsil.__file__).parent / "libvsil_video.so").exists()


# ---- the CLI's bytes ----

@pytest.mark.parametrize(
    "options",
    [
        {"technique": "silhouette", "iso": 0.45, "width_near": 5, "width_far": 1, "fill": "shaded"},
        {"technique": "illustrate", "effects": "boundary,silhouette,tone", "view": (40, 10)},
        {"technique": "demip", "size": (96, 64), "sphere_weight": 0.5, "depth_weight": 0.3},
        {"technique": "rightangle", "iso": 0.45, "fill": "tone", "param": "k_ty=0.4,k_ds=0.5",
         "light": (30, 70)},
        {"technique": "mip", "window": (0.2, 0.9), "ortho": True},
        {"technique": "lmip", "lmip_threshold": 0.5},
        {"technique": "semantic", "rules": "example"},
        {"technique": "illustrate", "tf": "ct-bone"},  # a preset by name, as --tf NAME
    ],
    ids=["silhouette", "illustrate", "demip", "rightangle_tone_fill", "mip", "lmip", "semantic",
         "illustrate_tf_preset"],
)
def test_render_matches_the_command_line_byte_for_byte(tmp_path, renderer, options):
    options = {"size": (120, 90), **options}
    args = ["render", "gen:spheres:64", "--out", str(tmp_path / "cli.png")]
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        if value is True:
            args.append(flag)
            continue
        if isinstance(value, tuple):
            value = ("x" if key == "size" else ",").join(str(v) for v in value)
        args += [flag, str(value)]
    depth_out = options["technique"] == "silhouette"
    if depth_out:
        args += ["--state-out", str(tmp_path / "state.png"), "--depth-out", str(tmp_path / "d.png")]
    if options["technique"] == "demip":
        args += ["--depth-out", str(tmp_path / "d.png")]
    run_cli(*args)

    frame = renderer.render("gen:spheres:64", **options)
    cli = np.asarray(Image.open(tmp_path / "cli.png").convert("RGBA"))
    assert frame.image.dtype == np.uint8 and frame.image.shape == cli.shape
    assert np.array_equal(frame.image, cli)
    if depth_out:
        state = np.asarray(Image.open(tmp_path / "state.png"))
        assert np.array_equal(frame.state.astype(np.int32) * 85, state.astype(np.int32))
        # The depth file keeps the line pixels' depth, quantized to 1/65534.
        lines = frame.state == 3
        depth = decode_depth(tmp_path / "d.png")
        assert lines.any()
        assert np.array_equal(np.isnan(depth), ~lines)
        assert np.nanmax(np.abs(depth[lines] - frame.depth[lines])) <= 0.5 / 65534 + 1e-9
    if options["technique"] == "demip":
        # The first hit's depth where a ray met the volume, none elsewhere: in the file as in
        # the frame.
        depth = decode_depth(tmp_path / "d.png")
        hit = ~np.isnan(frame.depth)
        assert hit.any() and not hit.all()
        assert np.array_equal(np.isnan(depth), ~hit)
        assert np.nanmax(np.abs(depth - frame.depth)) <= 0.5 / 65534 + 1e-9
    assert frame.metadata["parameters"]["technique"] == options["technique"]


def test_every_render_flag_has_its_keyword():
    help_text = run_cli("render", "--help").stdout
    flags = set(re.findall(r"--([a-z][a-z0-9-]+)", help_text))
    # What only the command writes (files) or prints is not a keyword of Renderer.render.
    flags -= {"help", "out", "state-out", "depth-out", "meta-out", "validate", "quiet"}
    assert {"iso", "width-near", "width-far", "technique", "size", "crop"} <= flags
    renderer = vsil.Renderer()
    for flag in sorted(flags):
        keyword = flag.replace("-", "_")
        # A value no flag accepts and a volume that cannot load: a ValueError (a TypeError for
        # a switch, which takes True or False), but never an unknown keyword.
        with pytest.raises((ValueError, TypeError)) as error:
            renderer.render("gen:no-such-generator:8", **{keyword: "-1e999,q"})
        assert "unknown keyword" not in str(error.value), flag
    with pytest.raises(TypeError, match="unknown keyword 'no_such_option'"):
        renderer.render("gen:sphere:8", no_such_option=1)
    # tf takes the presets by name as --tf does; an unknown one lists them.
    with pytest.raises(ValueError, match=r"--tf: unknown preset .*ct-bone.*ramp"):
        renderer.render("gen:sphere:8", technique="mip", tf="bone")
    # Flags render does not own in the module say where they belong instead of being ignored.
    with pytest.raises(ValueError, match=r"vsil.Renderer\(gl=...\)"):
        renderer.render("gen:sphere:8", gl="egl")
    with pytest.raises(ValueError, match=r"vsil.load\(path, crop=...\)"):
        renderer.render(vsil.generate("sphere", 8), crop="0:4,0:4,0:4")


# ---- volumes ----

def test_wrapping_an_array_copies_nothing(renderer):
    z, y, x = np.mgrid[0:24, 0:20, 0:16].astype(np.float32)
    array = np.ascontiguousarray(np.sqrt((x - 8) ** 2 + (y - 10) ** 2 + (z - 12) ** 2) < 6,
                                 dtype=np.float32)
    volume = vsil.Volume(array, spacing=(1, 1, 2), name="ball")
    assert volume.dims == (16, 20, 24) and volume.spacing == (1, 1, 2)
    assert volume.data is array and volume.dtype == np.float32
    assert volume.value_range == (0.0, 1.0)

    first = renderer.render(volume, iso=0.5, size=(64, 64))
    assert (first.state == 3).any()
    array[:] = 0  # in place: the texture keeps the old samples until upload
    with pytest.warns(UserWarning, match="outside the data's range 0 .. 0"):  # read in place
        assert np.array_equal(renderer.render(volume, iso=0.5, size=(64, 64)).state, first.state)
    renderer.upload(volume)
    with pytest.warns(UserWarning):
        assert not (renderer.render(volume, iso=0.5, size=(64, 64)).state == 3).any()


def test_a_volume_takes_the_renders_max_texture_mib(renderer):
    # gen:spheres:128 is an 8 MiB float32 texture: 11 bricks at 1 MiB, the same bytes (the
    # CLI's max_texture_mib test); the tiles march, which needs one texture, shows the bricks.
    volume = vsil.generate("spheres", 128)
    whole = renderer.render(volume, size=(96, 80), view=(37, -23))
    bricked = renderer.render(volume, size=(96, 80), view=(37, -23), max_texture_mib=1)
    assert np.array_equal(whole.image, bricked.image) and np.array_equal(whole.state, bricked.state)
    # silhouette's default pipeline, tiles, gives way to fast over bricks (the CLI's default too)
    assert whole.metadata["parameters"]["pipeline"] == "tiles"
    assert bricked.metadata["parameters"]["pipeline"] == "fast"
    with pytest.raises(ValueError, match="takes 11 bricks"):
        renderer.render(volume, size=(32, 32), pipeline="tiles", max_texture_mib=1)
    assert renderer.render(volume, size=(32, 32), pipeline="tiles").state.any()


def test_loaded_data_is_a_view_that_keeps_the_volume_alive():
    volume = vsil.generate("spheres", 32)
    data = volume.data
    assert data.shape == (32, 32, 32) and np.shares_memory(data, volume.data)
    assert data.base is not None
    del volume
    assert float(data.max()) > 0  # still readable: the view holds the volume


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.int16, np.float32])  # raw --type's
def test_a_raw_file_loads_as_the_array_that_wrote_it(tmp_path, dtype):
    rng = np.random.default_rng(7)
    array = rng.integers(0, 100, size=(5, 6, 7)).astype(dtype)
    path = tmp_path / "v.raw"
    array.tofile(path)
    volume = vsil.load(str(path), dims="7x6x5", type=np.dtype(dtype).name, spacing=(1, 2, 3))
    assert volume.dims == (7, 6, 5) and volume.spacing == (1, 2, 3)
    assert volume.data.dtype == dtype and np.array_equal(volume.data, array)
    cropped = vsil.load(str(path), dims="7x6x5", type=np.dtype(dtype).name, crop="1:4,0:6,2:5")
    assert np.array_equal(cropped.data, array[2:5, 0:6, 1:4])


def test_the_metadata_says_how_the_volume_was_held(renderer):
    # R16F where every sample is an integer of magnitude up to 2048 (exact in half floats), else
    # R32F; one texture at this size.
    ramp = np.arange(16 * 16 * 16).reshape(16, 16, 16)
    for array, expected in [(ramp.astype(np.uint8), "R16F"), (ramp.astype(np.uint16), "R32F"),
                            (ramp.astype(np.float32) / 7, "R32F")]:
        frame = renderer.render(vsil.Volume(array), size=(16, 16))
        assert frame.metadata["volume_texture"] == {"format": expected, "bricks": [1, 1, 1]}


# ---- errors ----

def test_bad_input_raises_value_error_with_the_cli_message(tmp_path, renderer):
    # A missing volume: FileNotFoundError (an OSError with errno and filename) holding the CLI's
    # one-line message, from load and from render with a path alike.
    missing = str(tmp_path / "missing.nrrd")
    cli = subprocess.run([VSIL, "render", missing, "--out", str(tmp_path / "x.png")],
                         capture_output=True, text=True)
    assert cli.returncode == 2
    for call in (lambda: vsil.load(missing), lambda: renderer.render(missing, size=(8, 8))):
        with pytest.raises(FileNotFoundError) as error:
            call()
        assert error.value.errno == errno.ENOENT and error.value.filename == missing
        assert cli.stderr.strip() == "vsil: " + error.value.strerror
    # A file that is there but bad stays a ValueError.
    (tmp_path / "bad.nrrd").write_text("not a volume")
    with pytest.raises(ValueError, match="bad.nrrd"):
        vsil.load(tmp_path / "bad.nrrd")

    with pytest.raises(ValueError, match="--size"):
        renderer.render("gen:sphere:16", size="0x0")
    with pytest.raises(ValueError, match="complex128 are not supported"):
        vsil.Volume(np.zeros((4, 4, 4), np.complex128))
    with pytest.raises(ValueError, match="3-dimensional"):
        vsil.Volume(np.zeros((4, 4), np.float32))
    with pytest.raises(ValueError, match="width"):
        vsil.broaden(np.zeros((8, 8), np.uint8), width=0)


@pytest.mark.parametrize("bad, what", [(np.nan, "is NaN"), (np.inf, "is infinite")])
def test_a_non_finite_sample_is_refused_as_the_cli_refuses_it(tmp_path, renderer, bad, what):
    samples = np.ones((4, 5, 6), np.float32)
    samples[2, 1, 3] = bad  # sample 2·30 + 1·6 + 3 = 69 in (z, y, x) order, as in the file
    with pytest.raises(ValueError) as error:
        vsil.Volume(samples)
    assert str(error.value) == f"vsil.Volume: sample 69 {what}"
    # Written in place after wrapping: refused at the upload, and by the renders after it (they
    # rendered the previous upload's texture without a word) until the samples are finite again.
    finite = np.ones((4, 5, 6), np.float32)
    volume = vsil.Volume(finite)
    renderer.render(volume, technique="mip", size=(8, 8))
    finite[2, 1, 3] = bad
    with pytest.raises(ValueError, match=f"sample 69 {what}"):
        renderer.upload(volume)
    with pytest.raises(ValueError, match=f"sample 69 {what}"):
        vsil.info(volume)  # once statistics of None
    with pytest.raises(ValueError, match=f"sample 69 {what}"):
        renderer.render(volume, technique="mip", size=(8, 8))
    finite[2, 1, 3] = 1
    assert renderer.render(volume, technique="mip", size=(8, 8)).image.shape == (8, 8, 4)
    raw = tmp_path / "bad.raw"
    samples.tofile(raw)
    cli = subprocess.run([VSIL, "render", str(raw), "--dims", "6x5x4", "--type", "float32",
                          "--out", str(tmp_path / "x.png")], capture_output=True, text=True)
    assert cli.returncode == 2 and not (tmp_path / "x.png").exists()
    assert cli.stderr.strip().endswith(f"bad.raw: sample 69 {what}")


def test_a_float64_sample_beyond_float32_is_named_as_the_cli_names_it(tmp_path):
    samples = np.ones((4, 5, 6), np.float64)
    samples[2, 1, 3] = -1e300  # finite, but infinite once converted to float32
    with pytest.raises(ValueError) as error:
        vsil.Volume(samples)
    assert str(error.value) == "vsil.Volume: sample 69 (-1e+300) is beyond the float32 range"
    nrrd = tmp_path / "big.nrrd"  # raw volumes take float32 at most; NRRD holds doubles
    nrrd.write_bytes(b"NRRD0004\ntype: double\ndimension: 3\nsizes: 6 5 4\nendian: little\n"
                     b"encoding: raw\n\n" + samples.astype("<f8").tobytes())
    cli = subprocess.run([VSIL, "info", str(nrrd)], capture_output=True, text=True)
    assert cli.returncode == 2
    assert cli.stderr.strip().endswith("big.nrrd: sample 69 (-1e+300) is beyond the float32 range")


def test_an_iso_outside_the_range_warns(renderer):
    with pytest.warns(UserWarning, match="outside the data's range"):
        renderer.render("gen:sphere:16", iso=1000, size=(32, 32))


def test_line_keywords_on_a_technique_without_lines_warn(renderer):
    with pytest.warns(UserWarning, match=r"--line-color: technique 'firsthit' draws no lines"):
        frame = renderer.render("gen:sphere:16", technique="firsthit", line_color="red",
                                size=(32, 32))
    assert frame.warnings == ["--line-color: technique 'firsthit' draws no lines or filled "
                              "pixels; ignored (the line flags go with silhouette and rightangle)"]


# ---- one process, many frames ----

def test_a_sweep_reuses_one_renderer(renderer):
    volume = vsil.generate("spheres", 64)
    silhouettes = []
    for iso in (0.2, 0.4, 0.6, 0.8):
        frame = renderer.render(volume, iso=iso, size=(96, 96))
        silhouettes.append(int((frame.state == 3).sum()))
        assert frame.metadata["parameters"]["iso"] == pytest.approx(iso)
    assert len(set(silhouettes)) == 4  # each iso value its own outline


# ---- postfx on arrays ----

def test_broaden_and_measure_a_line_of_known_width():
    lines = np.zeros((80, 120), np.uint8)
    lines[40, 10:110] = 1
    band = vsil.broaden(lines, width=7)
    assert set(np.unique(band)) == {0, 255}
    assert (band[:, 60] > 0).sum() == 7  # an integer width on an axis is exact
    report = vsil.measure_width(band)
    assert report["widths"]["median"] == pytest.approx(7, abs=0.25)
    assert report["samples"].shape[1] == 3


def test_depth_law_from_render_to_measurement(renderer):
    """The chain a width study builds: render with a depth law, measure width against depth."""
    frame = renderer.render("gen:spheres:96", iso=0.5, width_near=7, width_far=2,
                            size=(256, 256), view=(30, 20))
    lines = (frame.image[..., :3].max(axis=2) < 128).astype(np.uint8)
    report = vsil.measure_width(lines, depth=frame.depth, bins=4)
    bins = [b for b in report["by_depth"] if b["count"] > 20]
    assert len(bins) >= 2
    assert bins[0]["mean_width"] > bins[-1]["mean_width"] + 0.3  # near lines are wider
    # Each bin within half a pixel of the law w(d) = 7 - 5 d over the depths it holds.
    lo, hi = np.nanmin(frame.depth), np.nanmax(frame.depth)
    for b in bins:
        d0, d1 = max(b["depth_from"], lo), min(b["depth_to"], hi)
        assert 7 - 5 * d1 - 0.5 <= b["mean_width"] <= 7 - 5 * d0 + 0.5, b
    # broaden on the module's own arrays gives the render's lines.
    one_pixel = (frame.state == 3).astype(np.uint8)
    rebroadened = vsil.broaden(one_pixel, width_near=7, width_far=2, depth=frame.depth)
    assert np.array_equal(rebroadened > 0, lines > 0)


def test_width_against_depth_agrees_with_the_command_line_chain(tmp_path, renderer):
    """The README's study (depth of the silhouette pixels, as --depth-out keeps) gives the rows
    of `vsil render --depth-out` into `vsil measure-width --depth` (round 16: every first hit's
    depth gave other rows)."""
    args = dict(iso=0.5, width_near=7, width_far=2, size=(160, 160), view=(30, 20))
    frame = renderer.render("gen:spheres:96", **args)
    lines = (frame.image[..., :3].max(axis=2) < 128).astype(np.uint8)
    line_depth = np.where(frame.state == 3, frame.depth, np.nan)
    rows = vsil.measure_width(lines, depth=line_depth, bins=4)["by_depth"]
    run_cli("render", "gen:spheres:96", "--iso", "0.5", "--width-near", "7", "--width-far", "2",
            "--size", "160x160", "--view", "30,20", "--out", str(tmp_path / "o.png"),
            "--depth-out", str(tmp_path / "d.png"))
    run_cli("measure-width", str(tmp_path / "o.png"), "--depth", str(tmp_path / "d.png"),
            "--bins", "4", "--json", str(tmp_path / "m.json"))
    cli_rows = json.loads((tmp_path / "m.json").read_text())["by_depth"]
    assert [r["count"] for r in rows] == [r["count"] for r in cli_rows]
    assert sum(r["count"] for r in rows) > 100
    for mine, theirs in zip(rows, cli_rows):
        if theirs["mean_width"] is None:
            assert mine["mean_width"] is None
        else:
            assert mine["mean_width"] == pytest.approx(theirs["mean_width"], abs=1e-9)


# ---- threads ----

def _backends():
    """The back ends this machine gives a context on (VSIL_TEST_ALL_GL_BACKENDS=1: both must)."""
    found = []
    for backend in ("osmesa", "egl"):
        try:
            with vsil.Renderer(gl=backend):
                found.append(backend)
        except RuntimeError as error:
            if os.environ.get("VSIL_TEST_ALL_GL_BACKENDS") == "1":
                raise AssertionError(f"gl={backend}: {error}")
    return found


def test_renders_from_many_threads_take_turns_on_both_back_ends():
    """8 threads x 20 renders over one Renderer per back end and one per thread: every frame the
    one a single thread renders (GL state is process-wide: without the module's lock this
    crashed)."""
    import threading

    backends = _backends()
    assert backends, "no GL back end"
    volume = vsil.generate("spheres", 32)
    options = [{"iso": iso, "size": (48, 40), "view": (15 * k, 10)}
               for k, iso in enumerate((0.3, 0.5, 0.7, 0.4, 0.6))]
    renderers = {backend: vsil.Renderer(gl=backend) for backend in backends}
    expected = [renderers[backends[0]].render(volume, **o).image for o in options]
    failures = []

    def work(index):
        try:
            own = vsil.Renderer(gl=backends[index % len(backends)])
            for i in range(20):
                k = (index + i) % len(options)
                # Shared renderers, this thread's own one, and a path read in the turn.
                renderer = own if i % 3 == 0 else renderers[backends[i % len(backends)]]
                source = "gen:spheres:32" if i % 4 == 1 else volume
                image = renderer.render(source, **options[k]).image
                if not np.array_equal(image, expected[k]):
                    failures.append((index, i, renderer.gl["backend"]))
            own.close()
        except Exception as error:  # noqa: BLE001 - reported below with its thread
            failures.append((index, repr(error)))

    threads = [threading.Thread(target=work, args=(index,)) for index in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert failures == []
    for renderer in renderers.values():
        renderer.close()


def test_a_renderer_keeps_its_back_end_and_says_so():
    for backend in _backends():
        with vsil.Renderer(gl=backend) as renderer:
            assert renderer.gl["backend"] == backend
            frame = renderer.render("gen:sphere:16", size=(16, 16))
            assert frame.metadata["gl"]["backend"] == backend
            # The back end is the Renderer's: switching is making another one.
            with pytest.raises(ValueError, match=r"vsil.Renderer\(gl=...\)"):
                renderer.render("gen:sphere:16", gl="osmesa" if backend == "egl" else "egl")
        assert renderer.closed
        with pytest.raises(ValueError, match="closed"):
            renderer.render("gen:sphere:16")


# ---- the API as Python users expect it ----

def _technique_users(keyword):
    """The techniques a technique option's help names: "[silhouette, rightangle] ..."."""
    match = re.match(r"\[([a-z, ]+)\]", keyword["help"])
    return match.group(1).split(", ") if match else None


# Giving each option its default also gives ones the frame ignores (their warning).
@pytest.mark.filterwarnings("ignore:.*; ignored:UserWarning")
def test_the_signature_lists_every_keyword_with_a_default_that_renders_as_none_given(renderer):
    table = vsil._vsil._keywords("render")
    signature = inspect.signature(vsil.Renderer.render)
    keywords = {name: p for name, p in signature.parameters.items()
                if p.kind is inspect.Parameter.KEYWORD_ONLY}
    assert list(keywords) == [k["key"] for k in table]
    assert {"iso", "width_near", "technique", "size", "crop", "ra_exponent"} <= set(keywords)
    assert keywords["ra_exponent"].default == 8.0 and keywords["size"].default == (512, 512)
    assert keywords["technique"].default == "silhouette" and keywords["iso"].default is None
    assert "Literal['fast', 'paper', 'tiles']" in str(keywords["pipeline"].annotation)
    import pydoc  # what help() prints
    text = pydoc.render_doc(vsil.Renderer.render, renderer=pydoc.plaintext)
    assert "ra_exponent: 'Number' = 8.0" in text and "ra_exponent=8.0: [rightangle]" in text
    assert [p.name for p in inspect.signature(vsil.Renderer).parameters.values()] == [
        "gl", "gl_device"]
    assert "crop" in inspect.signature(vsil.load).parameters

    # Each default, given explicitly, renders what giving nothing renders: per technique, its own
    # options and the shared ones (the volume's come from the file, so not here).
    volume = vsil.generate("spheres", 32)
    shared = {k["key"]: k["default"] for k in table
              if k["default"] is not None and _technique_users(k) is None
              and k["group"] != "Raw volume layout (headerless files)"}
    for technique in table[0]["choices"]:
        given = dict(shared, technique=technique, size=(40, 32))
        # semantic's flatness included: it declares no default (leaving it out lets the rules
        # decide per sample, which no value says), so None; it once declared 0, which differs.
        given.update({k["key"]: k["default"] for k in table if k["default"] is not None
                      and technique in (_technique_users(k) or [])})
        plain = renderer.render(volume, technique=technique, size=(40, 32))
        explicit = renderer.render(volume, **given)
        assert np.array_equal(plain.image, explicit.image), (technique, given)


def test_the_stub_is_shipped_and_lists_the_keywords():
    import ast

    stub = pathlib.Path(vsil.__file__).with_name("__init__.pyi")
    assert pathlib.Path(vsil.__file__).with_name("py.typed").exists()
    tree = ast.parse(stub.read_text())
    classes = {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}
    assert {"Volume", "Frame", "Renderer"} <= set(classes)
    render = next(node for node in classes["Renderer"].body
                  if isinstance(node, ast.FunctionDef) and node.name == "render")
    assert [a.arg for a in render.args.kwonlyargs] == [k["key"] for k in vsil._vsil._keywords("render")]
    assert ast.unparse(render.returns) == "Frame"
    functions = {node.name for node in tree.body if isinstance(node, ast.FunctionDef)}
    assert {"load", "generate", "broaden", "measure_width"} <= functions


def test_wrong_types_are_type_errors_naming_the_keyword(renderer):
    for keywords, message in [({"iso": [1, 2]}, "iso takes a number, not list"),
                              ({"ortho": 1}, "ortho takes True or False, not int"),
                              ({"size": object()}, "size takes"),
                              ({"zoom": True}, "zoom takes a value, not a bool"),
                              ({"no_such": 1}, "unknown keyword 'no_such'")]:
        with pytest.raises(TypeError, match=re.escape(message)):
            renderer.render("gen:sphere:8", **keywords)
    with pytest.raises(TypeError, match="must be a vsil.Volume, a path or a gen: spec, not int"):
        renderer.render(42)
    with pytest.raises(TypeError, match="stride takes"):
        vsil.load("gen:sphere:8", stride=[2])
    # numpy numbers are numbers, and a value out of range stays a ValueError.
    a = renderer.render("gen:sphere:16", iso=np.float32(0.5), size=(np.int64(24), 20))
    b = renderer.render("gen:sphere:16", iso=0.5, size=(24, 20))
    assert np.array_equal(a.image, b.image)
    with pytest.raises(ValueError, match="--zoom"):
        renderer.render("gen:sphere:8", zoom=-1)


def test_a_light_list_is_the_flag_given_once_per_item(tmp_path, renderer):
    lights = [(30, 70), (-40, 10)]
    options = {"technique": "illustrate", "effects": "tone", "size": (64, 48)}
    frame = renderer.render("gen:spheres:32", light=lights, **options)
    run_cli("render", "gen:spheres:32", "--technique", "illustrate", "--effects", "tone",
            "--size", "64x48", "--light", "30,70", "--light", "-40,10",
            "--out", str(tmp_path / "cli.png"))
    assert np.array_equal(frame.image, np.asarray(Image.open(tmp_path / "cli.png").convert("RGBA")))
    one = renderer.render("gen:spheres:32", light=lights[:1], **options)
    assert not np.array_equal(one.image, frame.image)


def test_paths_may_be_path_like(tmp_path, renderer):
    array = np.zeros((6, 7, 8), np.uint8)
    array[2:4, 2:5, 3:6] = 200
    array.tofile(tmp_path / "v.raw")
    path = tmp_path / "v.raw"  # a pathlib.Path: os.PathLike
    volume = vsil.load(path, dims="8x7x6", type="uint8")
    assert np.array_equal(volume.data, array)
    by_path = renderer.render(path, dims=(8, 7, 6), type="uint8", iso=100, size=(32, 32))
    assert np.array_equal(by_path.image, renderer.render(volume, iso=100, size=(32, 32)).image)


def test_reprs_and_png_for_notebooks(renderer):
    assert re.fullmatch(r"<vsil.Renderer (osmesa|egl), .+>", repr(renderer))
    frame = renderer.render("gen:sphere:16", size=(48, 40))
    assert repr(frame) == "<vsil.Frame 48x40 silhouette>"
    assert repr(vsil.generate("sphere", 16)) == "<vsil.Volume sphere 16x16x16 float32>"
    png = frame._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(png)).convert("RGBA")), frame.image)
    closed = vsil.Renderer()
    closed.close()
    assert repr(closed) == "<vsil.Renderer closed>"
    with pytest.raises(ValueError, match="this renderer is closed"):
        with closed:
            pass


def test_a_dicom_series_reads_through_the_plugin_the_package_carries():
    import json

    # The DICOM reader is the plugin beside the extension (src/io/dicom_plugin.h), loaded at
    # the first DICOM volume: the same volume as the command reads.
    assert (pathlib.Path(vsil.__file__).parent / "libvsil_dicom.so").exists()
    folder = str(pathlib.Path(__file__).parents[2] / "tests/io/dicom/ct_rle")
    volume = vsil.load(folder)
    assert volume.data.shape == (5, 3, 4)  # z, y, x
    assert vsil.info(volume) == json.loads(run_cli("info", folder, "--json").stdout)
    maps = pathlib.Path("/proc/self/maps").read_text()
    assert "libvsil_dicom.so" in maps and "libgdcm" in maps


@pytest.mark.parametrize("folder", ["dicom_rle_segments", "dicom_rle_no_segments"])
def test_a_dicom_file_that_aborts_or_crashes_gdcm_raises_and_the_interpreter_goes_on(
        folder, renderer):
    # GDCM reads in a child process (src/io/dicom_child.h): one of its assert()s (the first
    # file) or a crash (SIGFPE, the second) ends the child, and this process raises the
    # command's one-line error.
    import sys

    path = str(pathlib.Path(__file__).parents[2] / "tests/bad_inputs" / folder / "slice.dcm")
    good = str(pathlib.Path(__file__).parents[2] / "tests/io/dicom/ct_rle")
    cli = subprocess.run([VSIL, "info", path], capture_output=True, text=True)
    assert cli.returncode == 2 and "GDCM" in cli.stderr
    for call in (lambda: vsil.load(path), lambda: vsil.info(path),
                 lambda: renderer.render(path, size=(8, 8))):
        with pytest.raises(ValueError) as error:
            call()
        assert "vsil: " + str(error.value) == cli.stderr.strip()
    assert vsil.load(good).data.shape == (5, 3, 4)
    # Quietly, with Python's faulthandler on (it would print a traceback from the crashing
    # child, as if this interpreter had crashed); on a descriptor of its own, as pytest has it
    # (vsil points descriptor 2 at /dev/null while GDCM runs).
    script = ("import faulthandler, os, vsil\nfaulthandler.enable(open(os.dup(2), 'w'))\n"
              f"try:\n    vsil.load({path!r})\nexcept ValueError as e:\n"
              f"    print('ValueError:', e)\nprint(vsil.load({good!r}).data.shape)\n")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert (run.returncode, run.stderr) == (0, "")
    assert run.stdout == "ValueError: " + cli.stderr.strip()[len("vsil: "):] + "\n(5, 3, 4)\n"


def test_info_is_what_the_command_prints(tmp_path):
    import json

    for spec in ["gen:spheres:24", "gen:marschner-lobb:20"]:
        cli = json.loads(run_cli("info", spec, "--json").stdout)
        assert vsil.info(spec) == cli
        assert vsil.info(vsil.load(spec)) == cli
    array = (np.arange(4 * 5 * 6) % 7).astype(np.uint16).reshape(4, 5, 6)
    array.tofile(tmp_path / "v.raw")
    cli = json.loads(run_cli("info", str(tmp_path / "v.raw"), "--dims", "6x5x4", "--type",
                             "uint16", "--crop", "1:5,:,:", "--json").stdout)
    assert vsil.info(tmp_path / "v.raw", dims=(6, 5, 4), type="uint16", crop="1:5,:,:") == cli
    assert cli["dims"] == [4, 5, 4] and cli["max"] == 6
    with pytest.raises(FileNotFoundError):
        vsil.info(tmp_path / "missing.vti")
    assert "crop" in inspect.signature(vsil.info).parameters


# ---- hostile input (issue 33): a ValueError of one line, never the end of the interpreter ----

def test_a_spacing_ratio_past_the_slice_limit_is_refused_before_any_work(renderer):
    volume = vsil.Volume(np.ones((4, 4, 4), np.float32), spacing=(1, 1, 1e-7))
    with pytest.raises(ValueError, match=r"spacing 1,1,1e-07 .* over the limit of 131072"):
        renderer.render(volume, size=(16, 16))


def test_json_nested_100000_deep_is_refused_not_a_crash(tmp_path, renderer):
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100000 + "]" * 100000)
    for key in ("tf", "style"):
        with pytest.raises(ValueError, match="nested more than 64 levels deep"):
            renderer.render("gen:sphere:16", technique="illustrate", size=(16, 16),
                            **{key: str(deep)})


@pytest.mark.parametrize("value", ["no", 0, 1, "", [], "True"])
def test_a_switch_takes_only_a_boolean(renderer, value):
    with pytest.raises(TypeError, match=r"ortho takes True or False"):
        renderer.render("gen:sphere:16", technique="mip", size=(16, 16), ortho=value)


def test_a_switch_given_false_is_off(renderer):
    on = renderer.render("gen:sphere:16", technique="mip", size=(16, 16), ortho=True)
    off = renderer.render("gen:sphere:16", technique="mip", size=(16, 16), ortho=False)
    assert on.metadata["camera"]["orthographic"] is True
    assert off.metadata["camera"]["orthographic"] is False


def test_broaden_refuses_a_mask_past_the_image_limit_before_any_work():
    # A 100000 x 1 view of a few bytes: the shape alone is refused (it ran 80 s, then OpenCV).
    huge = np.lib.stride_tricks.as_strided(np.zeros(1, np.uint8), shape=(100000, 100000),
                                           strides=(0, 0))
    with pytest.raises(ValueError, match=r"100000x100000 mask; each side must be 1 \.\. 16384"):
        vsil.broaden(huge, width=2)


@pytest.mark.parametrize("key", ["tf", "style", "effects", "window", "rules"])
def test_an_empty_value_is_refused_not_read_as_absent(renderer, key):
    technique = {"window": "mip", "rules": "semantic"}.get(key, "illustrate")
    with pytest.raises(ValueError, match="is empty: give a value, or leave the flag out"):
        renderer.render("gen:sphere:16", technique=technique, size=(16, 16), **{key: ""})
    with pytest.raises(ValueError, match="--crop: is empty"):
        vsil.load("gen:sphere:16", crop="")


# ---- native values (issue 34): each the same bytes as the flag's text ----

def _same_image(renderer, native, text, volume="gen:spheres:32", **common):
    common = {"size": (48, 40), **common}
    a = renderer.render(volume, **common, **native).image
    b = renderer.render(volume, **common, **text).image
    assert np.array_equal(a, b), (native, text)
    return a


def test_colours_take_rgb_tuples_in_0_1(renderer):
    image = _same_image(renderer, {"background": (0, 0, 0), "line_color": (1, 0.5, 0),
                                   "fill": "flat", "fill_color": (0.2, 0.4, 0.6, 1.0)},
                        {"background": "#000000", "line_color": "#ff8000",
                         "fill": "flat", "fill_color": "#336699ff"})
    assert (image[0, 0] == [0, 0, 0, 255]).all()  # the background is what was asked
    _same_image(renderer, {"color": (1, 1, 0.9411764705882353), "sketch_color": [0, 0, 1]},
                {"color": "#fffff0", "sketch_color": "blue"}, technique="illustrate",
                effects="sketch,tone")
    with pytest.raises(ValueError, match=r"background takes channels in \[0, 1\], not 255"):
        renderer.render("gen:sphere:8", background=(255, 0, 0))
    with pytest.raises(ValueError, match="3 or 4 numbers"):
        renderer.render("gen:sphere:8", background=(1, 0))
    with pytest.raises(TypeError, match="line_color takes numbers in"):
        renderer.render("gen:sphere:8", line_color=("red", 0, 0))


def test_crop_takes_slices_in_numpy_axis_order(tmp_path, renderer):
    array = (np.arange(10 * 12 * 14) % 251).astype(np.uint8).reshape(10, 12, 14)  # z, y, x
    array.tofile(tmp_path / "v.raw")
    raw = {"dims": (14, 12, 10), "type": "uint8"}
    for crop in [np.s_[2:9, :, 3:], np.s_[1:5], slice(None, 7), (slice(0, 10), slice(3, 4))]:
        volume = vsil.load(tmp_path / "v.raw", crop=crop, **raw)
        assert np.array_equal(volume.data, array[crop]), crop
    # The same bytes as the flag's text, whose order is x, y, z.
    by_slices = vsil.load(tmp_path / "v.raw", crop=np.s_[2:9, :, 3:], **raw)
    by_text = vsil.load(tmp_path / "v.raw", crop="3:,:,2:9", **raw)
    assert np.array_equal(by_slices.data, by_text.data)
    _same_image(renderer, {"crop": np.s_[2:9, :, 3:]}, {"crop": "3:,:,2:9"},
                volume=tmp_path / "v.raw", iso=100, **raw)
    with pytest.raises(ValueError, match="stride=N"):
        vsil.load(tmp_path / "v.raw", crop=np.s_[::2], **raw)
    with pytest.raises(ValueError, match="is not a voxel index"):
        vsil.load(tmp_path / "v.raw", crop=np.s_[-3:], **raw)
    with pytest.raises(ValueError, match="up to 3 slices"):
        vsil.load(tmp_path / "v.raw", crop=(slice(1, 2),) * 4, **raw)


def test_tf_takes_a_list_of_dicts_as_the_file_holds_it(tmp_path, renderer):
    import json

    tf = [{"value": 0.1, "color": "#000000", "opacity": 0},
          {"value": 0.5, "color": "#c08040", "opacity": 0.05},
          {"value": 1.0, "color": "#fffff0", "opacity": 0.8}]
    (tmp_path / "tf.json").write_text(json.dumps(tf))
    for technique in ("illustrate", "mip"):
        options = {"technique": technique, "size": (48, 40)}
        args = ["render", "gen:spheres:32", "--technique", technique, "--size", "48x40",
                "--tf", str(tmp_path / "tf.json"), "--out", str(tmp_path / "cli.png")]
        run_cli(*args)
        cli = np.asarray(Image.open(tmp_path / "cli.png").convert("RGBA"))
        native = renderer.render("gen:spheres:32", tf=tf, **options).image
        assert np.array_equal(native, cli), technique
        # A path object names the file, as the flag does.
        assert np.array_equal(renderer.render("gen:spheres:32", tf=tmp_path / "tf.json",
                                              **options).image, cli)
    # The CLI takes the JSON itself too (what the list becomes).
    run_cli("render", "gen:spheres:32", "--technique", "mip", "--size", "48x40", "--tf",
            json.dumps(tf), "--out", str(tmp_path / "inline.png"))
    assert np.array_equal(np.asarray(Image.open(tmp_path / "inline.png").convert("RGBA")), cli)
    with pytest.raises(ValueError, match=r"--tf: point 2: .*opacity"):
        renderer.render("gen:spheres:32", technique="mip", size=(8, 8),
                        tf=[tf[0], dict(tf[1], opacity=2)])
    # numpy's numbers, as numpy.linspace gives them, are the numbers they hold (round 19: a bare
    # "Object of type float64 is not JSON serializable"); what JSON lacks names the keyword.
    values = np.array([0.1, 0.5, 1.0], np.float32)
    from_numpy = [dict(point, value=value, opacity=np.float64(point["opacity"]))
                  for point, value in zip(tf, values)]
    assert np.array_equal(renderer.render("gen:spheres:32", tf=from_numpy, **options).image,
                          renderer.render("gen:spheres:32", tf=[dict(p, value=float(v)) for p, v
                                                                in zip(tf, values)],
                                          **options).image)
    assert np.array_equal(
        renderer.render("gen:spheres:32", technique="illustrate", size=(48, 40),
                        style={"effects": ["tone"], "parameters": {"k_ty": np.float32(0.25)}}).image,
        renderer.render("gen:spheres:32", technique="illustrate", size=(48, 40),
                        style={"effects": ["tone"], "parameters": {"k_ty": 0.25}}).image)
    with pytest.raises(TypeError, match=r"^vsil\.Renderer\.render: tf takes JSON values \(numbers, "
                                        r"texts, lists, dicts\), not complex$"):
        renderer.render("gen:spheres:32", technique="mip", tf=[dict(tf[0], value=1j)])
    with pytest.raises(ValueError, match=r"^vsil\.Renderer\.render: tf takes finite numbers, not "
                                         r"NaN or inf$"):
        renderer.render("gen:spheres:32", technique="mip", tf=[dict(tf[0], value=np.nan)])
    with pytest.raises(TypeError, match=r"^vsil\.Renderer\.render: style's dict keys must be texts$"):
        renderer.render("gen:spheres:32", technique="illustrate", style={"parameters": {np.int64(1): 2}})


def test_style_takes_a_dict_as_the_file_holds_it(tmp_path, renderer):
    import json

    style = {"effects": ["boundary", "tone"], "parameters": {"k_gc": 0.9}}
    (tmp_path / "style.json").write_text(json.dumps(style))
    _same_image(renderer, {"style": style}, {"style": str(tmp_path / "style.json")},
                technique="illustrate")


def test_rules_take_rule_text(tmp_path, renderer):
    rules = (pathlib.Path(__file__).parents[2] / "src/core/rules/example.rules").read_text()
    (tmp_path / "mine.rules").write_text(rules)
    image = _same_image(renderer, {"rules": rules}, {"rules": tmp_path / "mine.rules"},
                        technique="semantic")
    assert np.array_equal(image, renderer.render("gen:spheres:32", technique="semantic",
                                                 rules="example", size=(48, 40)).image)
    with pytest.raises(ValueError, match=r"--rules:1:"):
        renderer.render("gen:spheres:32", technique="semantic", size=(8, 8),
                        rules="attribute density from data { }")


def test_param_takes_a_dict_and_light_several_tuples(renderer):
    _same_image(renderer, {"param": {"k_ty": 0.4, "k_ds": 0.5}, "light": [(30, 70), (-40, 10)]},
                {"param": "k_ty=0.4,k_ds=0.5", "light": ["30,70", "-40,10"]},
                technique="illustrate", effects="tone,distance")


# ---- volumes of any dtype, strides and byte order ----

def _ball(dtype=np.float32):
    z, y, x = np.mgrid[0:20, 0:18, 0:16]
    return ((x - 8) ** 2 + (y - 9) ** 2 + (z - 10) ** 2 < 36).astype(dtype) * 100


@pytest.mark.parametrize("dtype, native", [(np.float64, np.float32), (np.int32, np.float32),
                                           (np.int64, np.float32), (np.uint32, np.float32),
                                           (np.float16, np.float32), (bool, np.uint8)])
def test_other_dtypes_convert_to_the_nearest_with_a_warning(renderer, dtype, native):
    array = _ball(dtype) if dtype is not bool else _ball() > 0
    name = np.dtype(dtype).name
    with pytest.warns(UserWarning, match=f"{name} samples converted to {np.dtype(native).name}"):
        volume = vsil.Volume(array)
    assert volume.dtype == native and np.array_equal(volume.data, array.astype(native))
    expected = renderer.render(vsil.Volume(array.astype(native)), iso=0.5, size=(40, 32))
    frame = renderer.render(volume, iso=0.5, size=(40, 32))
    assert np.array_equal(frame.image, expected.image) and (frame.state == 3).any()


@pytest.mark.parametrize("view, why", [
    (lambda a: a[:, :, ::-1], "non-C-contiguous"),
    (lambda a: np.asfortranarray(a), "non-C-contiguous"),
    (lambda a: np.repeat(a, 2, axis=2)[:, :, ::2], "non-C-contiguous"),
    (lambda a: a.astype(">f4"), "big-endian samples byte-swapped"),
    (lambda a: a.astype(">i2")[::-1], "big-endian samples byte-swapped; a non-C-contiguous"),
])
def test_any_strides_and_byte_order_are_copied_once_with_a_warning(renderer, view, why):
    array = view(_ball())
    with pytest.warns(UserWarning, match=why) as warned:
        volume = vsil.Volume(array)
    assert len(warned) == 1 and "one copy of" in str(warned[0].message)
    assert volume.data.flags.c_contiguous and volume.data.dtype.isnative
    assert np.array_equal(volume.data, array)
    native = np.ascontiguousarray(array, dtype=array.dtype.newbyteorder("="))
    expected = renderer.render(vsil.Volume(native), iso=50, size=(40, 32))
    assert np.array_equal(renderer.render(volume, iso=50, size=(40, 32)).image, expected.image)


def test_a_native_array_is_shared_without_a_warning():
    import warnings

    array = _ball()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert vsil.Volume(array).data is array


# ---- outputs and metadata as the command writes them ----

def test_outputs_a_technique_does_not_make_are_none(renderer):
    # As TechniqueInfo::outputs says, and --state-out / --depth-out refuse.
    mip = renderer.render("gen:spheres:32", technique="mip", size=(32, 32))
    assert mip.state is None and mip.depth is None
    demip = renderer.render("gen:spheres:32", technique="demip", size=(32, 32))
    assert demip.state is None and demip.depth.shape == (32, 32)
    silhouette = renderer.render("gen:spheres:32", size=(32, 32))
    assert silhouette.state.shape == (32, 32) and silhouette.depth.shape == (32, 32)
    for technique in vsil._vsil._keywords("render")[0]["choices"]:
        frame = renderer.render("gen:spheres:16", technique=technique, size=(16, 16))
        for output in ("state", "depth"):
            value = getattr(frame, output)
            assert value is None or value.shape == (16, 16), (technique, output)


def _without_timings(meta):
    """Less what differs from run to run (times; whether this process compiled the program
    before) and the output file only the command writes."""
    if isinstance(meta, dict):
        return {k: _without_timings(v) for k, v in meta.items()
                if not k.endswith("_ms") and k not in ("program_compiled", "out")}
    return meta


@pytest.mark.parametrize("technique", ["silhouette", "mip", "illustrate", "semantic"])
def test_metadata_is_what_meta_out_writes(tmp_path, renderer, technique):
    import json

    array = (np.arange(12 * 14 * 16) % 200).astype(np.uint8).reshape(12, 14, 16)
    array.tofile(tmp_path / "v.raw")
    args = ["--dims", "16x14x12", "--type", "uint8", "--crop", "1:15,:,2:", "--size", "40x32",
            "--technique", technique]
    run_cli("render", str(tmp_path / "v.raw"), *args, "--out", str(tmp_path / "x.png"),
            "--meta-out", str(tmp_path / "m.json"))
    cli = json.loads((tmp_path / "m.json").read_text())
    frame = renderer.render(tmp_path / "v.raw", dims=(16, 14, 12), type="uint8",
                            crop=np.s_[2:, :, 1:15], size=(40, 32), technique=technique)
    assert cli["dataset"]["read"]["crop"] == [[1, 15], [0, 14], [2, 12]]
    assert _without_timings(frame.metadata) == _without_timings(cli)
    # The stages the command times are there, less what only a process has (startup, write).
    assert {"read", "upload", "render"} <= set(frame.metadata["timings_ms"])


# ---- several volumes resident on one Renderer ----

def test_resident_volumes_switch_without_upload():
    first, second = vsil.generate("spheres", 32), vsil.Volume(_ball())
    with vsil.Renderer() as renderer:
        expected = [renderer.render(v, iso=0.5, size=(40, 32)).image for v in (first, second)]
        renderer.add_volume(first)
        renderer.add_volume(second)
        assert renderer.resident_volumes == 2
        uploads = renderer.uploads
        for i in range(6):
            frame = renderer.render((first, second)[i % 2], iso=0.5, size=(40, 32))
            assert np.array_equal(frame.image, expected[i % 2])
            assert frame.metadata["timings_ms"]["upload"] == 0
        assert renderer.uploads == uploads  # switching uploaded nothing
        # A volume that is not resident takes the main texture, one upload per switch.
        third = vsil.generate("sphere", 16)
        renderer.render(third, size=(16, 16))
        renderer.render(first, size=(16, 16))
        renderer.render(third, size=(16, 16))
        assert renderer.uploads == uploads + 1
        # In place changes reach a resident volume's texture with upload, as any volume's.
        renderer.upload(second)
        assert renderer.uploads == uploads + 2
        renderer.remove_volume(first)
        assert renderer.resident_volumes == 1
        assert np.array_equal(renderer.render(first, iso=0.5, size=(40, 32)).image, expected[0])
        with pytest.raises(ValueError, match="not resident"):
            renderer.remove_volume(first)
        # Without resident volumes the same switching uploads each time.
        before = renderer.uploads
        renderer.remove_volume(second)
        for i in range(4):
            renderer.render((first, second)[i % 2], iso=0.5, size=(40, 32))
        assert renderer.uploads == before + 4 - 1  # first is already in the main texture


# ---- animate: vsil animate's frames and video from one call ----

@pytest.mark.parametrize("container", ["avi", "mp4"])
def test_animate_writes_the_video_vsil_animate_writes(tmp_path, renderer, container):
    frames = renderer.animate("gen:spheres:32", frames=4, orbit=90, sweep={"iso": (0.3, 0.6)},
                              video=tmp_path / f"py.{container}", size=(48, 40))
    run_cli("animate", "gen:spheres:32", "--frames", "4", "--orbit", "90", "--sweep",
            "iso=0.3:0.6", "--video", str(tmp_path / f"cli.{container}"), "--out-dir",
            str(tmp_path / "frames"), "--size", "48x40", "--quiet")
    assert (tmp_path / f"py.{container}").read_bytes() == (tmp_path / f"cli.{container}").read_bytes()
    assert len(frames) == 4 and frames[1].metadata["swept"] == {"iso": pytest.approx(0.4)}
    for i, frame in enumerate(frames):
        png = np.asarray(Image.open(tmp_path / "frames" / f"frame_{i:04d}.png").convert("RGBA"))
        assert np.array_equal(frame.image, png), i
    assert len({f.image.tobytes() for f in frames}) == 4


def test_animate_sweeps_python_names_and_warns_of_what_every_frame_ignores(renderer):
    """sweep= takes the keywords' spelling (sphere_weight); an option ignored only in some frames
    (the colour sphere's rotation while its swept weight is 0) is not said to be ignored, one
    ignored in every frame is, once."""
    import warnings as python_warnings
    with python_warnings.catch_warnings(record=True) as caught:
        python_warnings.simplefilter("always")
        frames = renderer.animate("gen:spheres:32", technique="demip", frames=3, size=(16, 16),
                                  sweep={"sphere_weight": (0, 1)}, sphere_rotate=(90, 0))
        assert not [w for w in caught if "ignored" in str(w.message)], [str(w.message) for w in caught]
        assert "ignored" in frames[0].warnings[0]  # frame 0 itself does ignore it
        renderer.animate("gen:spheres:32", technique="demip", frames=3, size=(16, 16),
                         sphere_rotate=(90, 0))
    said = [str(w.message) for w in caught if "ignored" in str(w.message)]
    assert said == ["vsil: --sphere-rotate: the colour sphere is off (--sphere-weight 0, no "
                    "--legend); ignored"], said


def test_a_numpy_vector_serves_as_a_pair_and_a_0d_array_as_a_number(renderer):
    """view=np.array([60, 20]) read as its repr '[60 20]' and was refused."""
    volume = vsil.generate("spheres", 32)
    expected = renderer.render(volume, view=(60, 20), zoom=1.5, size=(16, 16)).image
    given = renderer.render(volume, view=np.array([60, 20]), zoom=np.array(1.5), size=(16, 16))
    assert np.array_equal(given.image, expected)


@pytest.mark.parametrize("arguments, says", [
    (dict(frames="010"), "frames takes an int, not str"),
    (dict(frames=True), "frames takes an int, not bool"),
    (dict(frames=2, orbit="0x10"), "orbit takes a number, not str"),
    (dict(frames=2, fps=None), "fps takes a number, not NoneType"),
    (dict(frames=2, keep_frames=1), "keep_frames takes True or False, not int")])
def test_animate_arguments_of_the_wrong_type_are_one_line(renderer, arguments, says):
    with pytest.raises(TypeError) as error:
        renderer.animate("gen:sphere:16", size=(16, 16), **arguments)
    assert str(error.value) == "vsil.Renderer.animate: " + says


def test_broaden_refuses_a_depth_beside_one_width_and_bools():
    lines = np.zeros((32, 32), np.uint8)
    lines[16, 4:28] = 1
    with pytest.raises(ValueError, match="not both"):
        vsil.broaden(lines, width=3, depth=np.zeros((32, 32), np.float32))
    with pytest.raises(TypeError, match="width takes a number, not bool"):
        vsil.broaden(lines, width=True)
    with pytest.raises(TypeError, match="bins takes a number, not bool"):
        vsil.measure_width(lines, bins=True)


def test_animate_moves_the_view_and_checks_its_input(tmp_path, renderer):
    volume = vsil.generate("spheres", 32)
    frames = renderer.animate(volume, frames=3, view_from=(0, 0), view_to=(90, 30), size=(32, 32))
    # Each frame the render of its view: the middle one at (45, 15).
    for frame, view in zip(frames, [(0, 0), (45, 15), (90, 30)]):
        assert np.array_equal(frame.image, renderer.render(volume, view=view, size=(32, 32)).image)
    # Keeping neither the frames nor a video would render for nothing.
    with pytest.raises(ValueError, match="keep_frames=False without video="):
        renderer.animate(volume, frames=2, size=(32, 32), keep_frames=False)
    assert renderer.animate(volume, frames=2, size=(32, 32), keep_frames=False,
                            video=tmp_path / "kept.avi") == []
    assert (tmp_path / "kept.avi").stat().st_size > 0
    with pytest.raises(ValueError, match="--video"):
        renderer.animate(volume, frames=2, size=(33, 32), video=tmp_path / "odd.avi")
    assert not (tmp_path / "odd.avi").exists()
    with pytest.raises(ValueError, match="no_such"):
        renderer.animate(volume, frames=2, sweep=["no_such=1:2"])
    with pytest.raises(ValueError, match="together"):
        renderer.animate(volume, frames=2, view_from=(0, 0))


def test_animate_refuses_what_its_frames_would_overwrite(renderer):
    """As vsil animate (round 16: the given value was dropped without a word): a keyword a sweep
    sets on every frame, and view= beside view_from/view_to."""
    with pytest.raises(ValueError, match=r"sweep iso=30:60: iso= is given too"):
        renderer.animate("gen:spheres:16", frames=2, size=(16, 16), iso=40,
                         sweep={"iso": (30, 60)})
    with pytest.raises(ValueError, match=r"width_near= is given too"):
        renderer.animate("gen:spheres:16", frames=2, size=(16, 16), width_near=3,
                         width_far=1, sweep=["width-near=2:4"])
    with pytest.raises(ValueError, match=r"view= is given too"):
        renderer.animate("gen:spheres:16", frames=2, size=(16, 16), view=(10, 10),
                         view_from=(0, 0), view_to=(90, 0))
    # The width law is one: a width sweep beside the other kind of law, or one end swept
    # without the other (round 19: the given law was dropped, a far width of 3 taken unsaid).
    with pytest.raises(ValueError, match=r"--width-near is given too, and the sweep sets the "
                                         r"line width"):
        renderer.animate("gen:spheres:16", frames=2, size=(16, 16), width_near=1, width_far=3,
                         sweep=["width=1:8"])
    with pytest.raises(ValueError, match=r"needs --sweep width-far too"):
        renderer.animate("gen:spheres:16", frames=2, size=(16, 16), sweep=["width-near=1:8"])
    frames = renderer.animate("gen:spheres:16", frames=2, size=(16, 16),
                              sweep=["width-near=1:8", "width-far=2:1"])
    assert [f.metadata["parameters"]["width_near"] for f in frames] == [1, 8]


def test_animate_stops_at_a_signal_between_frames(tmp_path, renderer):
    """A signal handler's exception (Ctrl-C's KeyboardInterrupt alike) ends animate at the next
    frame, and the video is not written (round 16: it came only after every frame, the video
    whole)."""
    import signal
    import time

    class Stop(Exception):
        pass

    def stop(signum, frame):
        raise Stop()

    previous = signal.signal(signal.SIGALRM, stop)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        start = time.monotonic()
        with pytest.raises(Stop):
            renderer.animate("gen:spheres:32", frames=2000, size=(32, 32),
                             video=tmp_path / "stopped.avi")
        elapsed = time.monotonic() - start
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert not (tmp_path / "stopped.avi").exists()
    assert list(tmp_path.iterdir()) == []  # nor its temporary
    assert elapsed < 10, elapsed


def test_generate_upload_and_add_volume_refuse_wrong_types_in_one_line(renderer):
    """generate, upload and add_volume name the argument in one line (round 16: pybind11's
    text of several lines), and a bool is no size."""
    for call, says in [(lambda: vsil.generate(b"spheres"), "vsil.generate: name takes a str"),
                       (lambda: vsil.generate("spheres", True), "vsil.generate: size takes an int"),
                       (lambda: renderer.upload("gen:spheres:8"),
                        "vsil.Renderer.upload: volume takes a vsil.Volume, not str"),
                       (lambda: renderer.add_volume(np.zeros((4, 4, 4))),
                        "vsil.Renderer.add_volume: volume takes a vsil.Volume, not ndarray"),
                       (lambda: renderer.add_volume(vsil.generate("spheres", 8), 1.5),
                        "max_texture_mib takes an int, not float")]:
        with pytest.raises(TypeError) as error:
            call()
        assert says in str(error.value) and "\n" not in str(error.value), str(error.value)


def test_load_refuses_the_upload_keyword_it_would_ignore():
    """max_texture_mib decides how render cuts the volume into textures; load took it and
    ignored it (round 16)."""
    with pytest.raises(TypeError, match="max_texture_mib is a keyword of render"):
        vsil.load("gen:spheres:16", max_texture_mib=1)
    assert "max_texture_mib" not in inspect.signature(vsil.load).parameters


def test_warnings_name_the_callers_line(renderer):
    """A warning is attributed to the line that called vsil, not to vsil's own wrappers."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        renderer.render("gen:spheres:16", size=(16, 16), technique="mip", width=3)
        vsil.measure_width(np.ones((40, 40), np.uint8))
    assert len(caught) == 2, [str(w.message) for w in caught]
    for warning in caught:
        assert warning.filename == __file__, (warning.filename, str(warning.message))


# Giving each option its default also gives ones the frame ignores (their warning).
@pytest.mark.filterwarnings("ignore:.*; ignored:UserWarning")
def test_every_technique_options_default_is_the_one_the_command_line_states(renderer):
    """The CLI's --help "(default X" against inspect.signature, for every option of every
    technique: numbers equal, 'off' is False, a word is the keyword's default or, where the
    signature says None, renders what leaving it out renders; prose (derived) is None."""
    help_text = run_cli("render", "--help").stdout
    signature = inspect.signature(vsil.Renderer.render).parameters
    table = vsil._vsil._keywords("render")
    checked = 0
    for keyword in table:
        users = _technique_users(keyword)
        if not users:
            continue
        line = next(l for l in help_text.splitlines() if l.strip().startswith(keyword["flag"] + " "))
        match = re.search(r"\(default ((?:[^,()]|,(?! ))*)", line)  # to ", " or a parenthesis
        if not match:
            continue  # pipeline: a default per technique, in words
        stated, default = match.group(1).strip(), signature[keyword["key"]].default
        numbers = re.fullmatch(r"-?[0-9.]+(,-?[0-9.]+)*", stated)
        if numbers:
            values = tuple(float(v) for v in stated.split(","))
            got = default if isinstance(default, tuple) else (default,)
            assert tuple(float(v) for v in got) == values, keyword["key"]
        elif stated == "off":
            assert default is False, keyword["key"]
        elif re.fullmatch(r"[a-z-]+", stated):
            if default is None:  # the word, given, renders what leaving it out renders
                plain = renderer.render("gen:spheres:16", technique=users[0], size=(24, 24))
                given = renderer.render("gen:spheres:16", technique=users[0], size=(24, 24),
                                        **{keyword["key"]: stated})
                assert np.array_equal(plain.image, given.image), keyword["key"]
            else:
                assert default == stated, keyword["key"]
        else:
            assert default is None, (keyword["key"], stated, default)
        checked += 1
    assert checked >= 15
    assert signature["flatness"].default is None


def test_closing_a_renderer_while_another_thread_uses_it_raises_there_not_crashes():
    """close() from one thread while another renders, uploads, animates or reads .gl: the other
    gets ValueError ("closed"), whichever of them takes the GL lock first (the job used to be
    looked up before the wait and used after it: a segfault in every run). Run in a child: a
    crash fails.

    One clean-clone CI (stop 56) saw the child die of SIGSEGV once after that fix, with no stack;
    about 1000 runs since (loaded, pinned to one core, random timings) never did. So a child that
    dies of a signal runs once more, and the test fails if that one dies too or reports anything
    but "closed" (the old bug crashed every run); the first death's stack (faulthandler) is
    reported as a warning, for the cause to be found."""
    script = r"""
import random, sys, threading, time
import vsil
random.seed(7)
volume = vsil.generate("spheres", 32)
calls = {
    "render": lambda r: r.render(volume, size=(48, 48)),
    "upload": lambda r: r.upload(volume),
    "animate": lambda r: r.animate(volume, frames=2, size=(32, 32)),
    "gl": lambda r: r.gl,
}
for name, call in calls.items():
    for trial in range(25):
        renderer = vsil.Renderer()
        errors = []
        def loop():
            try:
                while True:
                    call(renderer)
            except ValueError as error:
                if "closed" not in str(error):
                    errors.append(repr(error))
        thread = threading.Thread(target=loop)
        thread.start()
        time.sleep(random.uniform(0, 0.03))
        renderer.close()
        thread.join()
        if errors:
            sys.exit(f"{name}: {errors[0]}")
print("ok")
"""
    def run_child():
        return subprocess.run([sys.executable, "-X", "faulthandler", "-c", script],
                              capture_output=True, text=True, timeout=600)
    result = run_child()
    if result.returncode < 0:
        warnings.warn(f"close race: the child died of signal {-result.returncode} once; "
                      f"ran it again. Its stack: {result.stderr[-3000:]}")
        result = run_child()
    assert result.returncode == 0, (result.returncode, result.stderr[-2000:])
    assert result.stdout.strip() == "ok"


def test_a_file_name_that_is_not_utf8_loads_renders_and_is_named_in_errors(tmp_path):
    """Linux file names are bytes; Python holds one that is not UTF-8 with lone surrogates
    (os.fsdecode). load, info and render take such a name, an error names it in a ValueError,
    and the metadata (JSON) writes U+FFFD for the byte. They once raised pybind11's multi-line
    cast errors."""
    folder = os.fsencode(tmp_path)
    name = os.fsdecode(folder + b"/bad\xffname.nrrd")
    with open(name, "wb") as file:
        file.write(b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n"
                   + bytes([64] * 8))
    volume = vsil.load(name)
    assert volume.dims == (2, 2, 2)
    # Its name as os.fsdecode gives it (round 15: UnicodeDecodeError from repr, source, name).
    assert volume.source == name and volume.name == "bad\udcffname"
    assert "bad\udcffname" in repr(volume)
    assert vsil.info(name)["source"].endswith("bad\ufffdname.nrrd")
    with vsil.Renderer() as renderer:
        frame = renderer.render(pathlib.Path(name), size=(16, 16))
    assert "bad\ufffdname.nrrd" in str(frame.metadata)
    cut = os.fsdecode(folder + b"/cut\xfe.nrrd")
    with open(cut, "wb") as file:
        file.write(b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n@@")
    with pytest.raises(ValueError) as error:
        vsil.load(cut)
    assert str(error.value).startswith(cut + ": ")
    with pytest.raises(FileNotFoundError) as missing:
        vsil.load(os.fsdecode(folder + b"/none\xfd.nrrd"))
    assert missing.value.filename == os.fsdecode(folder + b"/none\xfd.nrrd")


def test_measure_width_reads_masks_as_non_zero_and_refuses_depths_outside_0_1():
    """A mask is non-zero = line whatever its dtype (0.5 was cast to 0: no lines, no error); a
    NaN mask, a depth of another dtype (a depth image's uint16 codes) or outside [0, 1] is
    refused (each landed in the first or last bin); no sample with a depth warns; an empty bin's
    widths are None."""
    lines = np.zeros((40, 40), np.uint8)
    lines[10:14, 5:35] = 1  # a band 4 px wide
    counted = vsil.measure_width(lines)["widths"]["count"]
    assert counted > 0
    assert vsil.measure_width(lines * 0.5)["widths"]["count"] == counted
    with pytest.raises(ValueError, match="NaN"):
        vsil.measure_width(np.where(lines > 0, np.nan, 0.0))
    depth = np.full(lines.shape, np.nan, np.float32)
    depth[lines > 0] = 0.25
    report = vsil.measure_width(lines, depth=depth, bins=4)
    assert [b["count"] > 0 for b in report["by_depth"]] == [False, True, False, False]
    assert report["by_depth"][0]["mean_width"] is None
    for bad in (np.inf, -1.0, 2.0):
        outside = depth.copy()
        outside[12, 20] = bad
        with pytest.raises(ValueError, match=r"depth\[12, 20\]"):
            vsil.measure_width(lines, depth=outside)
    with pytest.raises(TypeError, match="floats in"):
        vsil.measure_width(lines, depth=(np.nan_to_num(depth) * 65534).astype(np.uint16))
    with pytest.warns(UserWarning, match="has a depth"):
        vsil.measure_width(lines, depth=np.full(lines.shape, np.nan, np.float32))


@pytest.mark.parametrize("call", [lambda: vsil.measure_width(None),
                                  lambda: vsil.measure_width(np.ones((4, 4)), bins=2.5),
                                  lambda: vsil.broaden(np.ones((4, 4), np.uint8), width="3")])
def test_arguments_of_the_wrong_type_are_one_line_naming_the_function(call):
    """pybind11's own message spans several lines (signatures, a blank line, what was given)."""
    with pytest.raises(TypeError) as error:
        call()
    text = str(error.value)
    assert "\n" not in text and re.match(r"vsil\.(measure_width|broaden): takes \(lines", text), text


def test_measure_width_and_broaden_name_an_unknown_keyword_and_describe_arrays_briefly():
    lines = np.zeros((64, 64), np.uint8)
    for function in (vsil.measure_width, vsil.broaden):
        with pytest.raises(ValueError, match=r"expected a 2-dimensional line mask \(non-zero = "
                                             r"line\), not a uint8 array of shape \(64, 64, 4\)$"):
            function(np.zeros((64, 64, 4), np.uint8), **({"width": 2} if function is vsil.broaden
                                                         else {}))
    with pytest.raises(TypeError, match=r"^vsil\.measure_width: unknown keyword 'bogus' \(it takes "
                                        r"lines, depth, bins, bin_width\)$"):
        vsil.measure_width(lines, bogus=1)
    with pytest.raises(TypeError, match=r"^vsil\.broaden: unknown keyword 'widht'"):
        vsil.broaden(lines, widht=3)
    # A wrong type names the array by dtype and shape, not its 4096 elements.
    with pytest.raises(TypeError) as error:
        vsil.broaden(lines, width="3")
    assert str(error.value).endswith("not (a uint8 array of shape (64, 64), width=str '3')"), \
        error.value


@pytest.mark.parametrize("arguments, says", [
    (dict(array=None), "array takes a numpy array (z, y, x), not NoneType"),
    (dict(spacing="1,1,1"), "spacing takes three numbers (x, y, z), not str '1,1,1'"),
    (dict(spacing=(True, 1, 1)), "spacing takes three numbers (x, y, z), not tuple (True, 1, 1)"),
    (dict(spacing=(1, 1)), "spacing takes three numbers (x, y, z), not tuple (1, 1)"),
    (dict(name=None), "name takes a str, not NoneType")])
def test_volume_arguments_of_the_wrong_type_are_one_line(arguments, says):
    """vsil.Volume's constructor said pybind11's several lines (the signature, what it was
    given); a bool is not a number of the spacing."""
    given = dict(array=np.zeros((2, 2, 2), np.uint8))
    given.update(arguments)
    with pytest.raises(TypeError) as error:
        vsil.Volume(**given)
    assert str(error.value) == "vsil.Volume: " + says


def test_volume_takes_the_spacing_as_any_three_numbers():
    """A list, a numpy array or numpy scalars serve as the spacing, as before."""
    array = np.zeros((2, 2, 2), np.uint8)
    for spacing in ([1, 2, 3], np.array([1.0, 2.0, 3.0]), (np.float32(1), np.int64(2), 3.0)):
        assert vsil.Volume(array, spacing=spacing).spacing == (1.0, 2.0, 3.0)
    with pytest.warns(UserWarning, match="converted to float32"):
        assert vsil.Volume([[[1, 2], [3, 4]]]).dims == (2, 2, 1)
