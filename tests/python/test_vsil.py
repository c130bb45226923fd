"""The Python module against the command line, and on its own: round trips to the CLI's bytes,
zero-copy wrapping, exceptions, a parameter sweep in one process, postfx on arrays.

Run by ctest (tests/CMakeLists.txt) with PYTHONPATH=build/python and VSIL_BINARY set."""

import os
import re
import subprocess

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
    ],
    ids=["silhouette", "illustrate", "demip", "rightangle_tone_fill", "mip", "lmip", "semantic"],
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
        # A value no flag accepts and a volume that cannot load: either way a ValueError, but
        # never an unknown keyword.
        with pytest.raises(ValueError) as error:
            renderer.render("gen:no-such-generator:8", **{keyword: "-1e999,q"})
        assert "unknown keyword" not in str(error.value), flag
    with pytest.raises(ValueError, match="unknown keyword 'no_such_option'"):
        renderer.render("gen:sphere:8", no_such_option=1)
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
    missing = str(tmp_path / "missing.nrrd")
    with pytest.raises(ValueError, match="missing.nrrd"):
        vsil.load(missing)
    cli = subprocess.run([VSIL, "render", missing, "--out", str(tmp_path / "x.png")],
                         capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(ValueError) as error:
        vsil.load(missing)
    assert cli.stderr.strip() == "vsil: " + str(error.value)

    with pytest.raises(ValueError, match="--size"):
        renderer.render("gen:sphere:16", size="0x0")
    with pytest.raises(ValueError, match="float64"):
        vsil.Volume(np.zeros((4, 4, 4)))
    with pytest.raises(ValueError, match="C-contiguous"):
        vsil.Volume(np.zeros((4, 4, 8), np.float32)[:, :, ::2])
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
    # Written in place after wrapping: refused at the upload, the renderer keeps what it had.
    finite = np.ones((4, 5, 6), np.float32)
    volume = vsil.Volume(finite)
    renderer.render(volume, technique="mip", size=(8, 8))
    finite[2, 1, 3] = bad
    with pytest.raises(ValueError, match=f"sample 69 {what}"):
        renderer.upload(volume)
    assert renderer.render(volume, technique="mip", size=(8, 8)).image.shape == (8, 8, 4)
    raw = tmp_path / "bad.raw"
    samples.tofile(raw)
    cli = subprocess.run([VSIL, "render", str(raw), "--dims", "6x5x4", "--type", "float32",
                          "--out", str(tmp_path / "x.png")], capture_output=True, text=True)
    assert cli.returncode == 2 and not (tmp_path / "x.png").exists()
    assert cli.stderr.strip().endswith(f"bad.raw: sample 69 {what}")


def test_an_iso_outside_the_range_warns(renderer):
    with pytest.warns(UserWarning, match="outside the data's range"):
        renderer.render("gen:sphere:16", iso=1000, size=(32, 32))


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
