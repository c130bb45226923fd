#!/usr/bin/python3
"""Peer measurement: VTK's GPU volume mapper in MIP mode beside vsil's MIP, in one run.

Issue 11 asked for VTK's GPU ray caster in maximum-intensity mode measured beside vsil's `mip`
on the Bonsai at 512²; issue 36 asks for vsil's MIP ahead of it on at least 4 of the 5 classic
datasets of the dv1 table (aneurism, bonsai, engine, teddybear, tooth), with DEMIP within 1.15×
MIP. This script times both renderers on each dataset, alternating, and prints a table and JSON.

It is a peer measurement, not part of CI or bootstrap. Needs Debian's VTK bindings and a virtual
X server (VTK 9.1 in bookworm renders through GLX):

    apt-get install -y --no-install-recommends python3-vtk9 xvfb xauth
    xvfb-run -a -s "-screen 0 1024x768x24" /usr/bin/python3 bench/peers/vtk_mip.py \
        --vsil build/vsil --json vtk_mip.json --images /tmp/vtk_mip

Both sides render on Mesa's llvmpipe with LP_NUM_THREADS threads (2 unless already set; on a
2-core machine that is llvmpipe's default, one thread per core). Both show the same picture:

- The window: vsil's default for the dataset (Otsu's threshold to the 99.5th percentile above
  it), read from `vsil render --meta-out` (parameters.window). VTK maps it the same way: a grey
  ramp black at LO to white at HI, opacity 0 at or below LO and 1 above it (VTK's MIP takes each
  ray's maximum, then classifies it, as vsil's finishing pass does).
- Sampling: vsil puts one slice per voxel along the view direction (anisotropic spacing
  counted: slicer.cpp planSlices) and samples each pixel's ray where it crosses the slices; VTK
  samples each ray every SampleDistance world units from where it enters the box. VTK's sample
  distance is set per frame to vsil's step between slices in world units, 1 / |d / spacing| for
  the unit view direction d (1 voxel for the isotropic volumes; for the teddybear, 2.8 × 2.8 × 5
  mm, between 2.8 and 5 mm as the view turns), no automatic adjustment, image sample distance 1.
  Along the central ray both take the same number of samples; vsil's off-centre rays cross the
  planes slightly farther apart (1/cos of the ray's angle to the view axis: up to about 1.07
  in the corners of a 30° field of view), VTK's keep their distance: vsil takes up to ~7% fewer
  samples on those rays.
- What differs by design: vsil's march starts each ray where it first enters a brick (8³
  voxels) whose values can reach the window's low end and stops it where it leaves such bricks
  for good (empty-space skipping); VTK's mapper samples every ray from box entry to exit.
- Timed per frame. VTK: Render() and a readback of the RGBA pixels (the readback waits for the
  frame to finish). vsil: `vsil bench --table dv1 --only DATASET`, whose columns (MIP, DEMIP,
  DEMIP with the colour sphere, DVR) take turns frame by frame; timed in-process:
  Renderer::render (slicing, glFinish, readback). The MIP and DEMIP columns are reported, and
  DEMIP/MIP from the same frames.
- The same orbit as the dv1 table: warm-up frames from azimuth 30°, elevation 20°; timed frame
  i from azimuth 30° + 3.6°·i, elevation 20°; perspective, 30° vertical field of view, the
  volume's bounding sphere filling the window (vsil's default camera, src/core/camera.cpp).
- Per dataset, VTK and vsil blocks (warm-up + timed frames each) alternate --rounds times, so
  that load from other processes falls on both alike. Reported: per renderer the median of its
  blocks' median frame times, each block's median, and VTK/vsil in frame time (> 1: vsil is
  faster); the load average at the start and after every block.
"""

import argparse
import json
import math
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("LP_NUM_THREADS", "2")  # before VTK loads Mesa

import numpy  # noqa: E402
import vtk  # noqa: E402  (Debian: python3-vtk9)
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402

ORBIT_START_DEG, ORBIT_STEP_DEG, ELEVATION_DEG = 30.0, 3.6, 20.0  # dv1's orbit
FOV_Y_DEG = 30.0  # vsil's default perspective
# The dv1 table's datasets (bench/tables/dv1_table.cpp kDatasets): name -> file.
DATASETS = {
    "aneurism": "aneurism.vti",
    "bonsai": "bonsai.vti",
    "engine": "engine.vti",
    "teddybear": "teddybear_128x128x62_uint8.nhdr",
    "tooth": "tooth.nrrd",
}


def load_average():
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def read_nrrd(path):
    """uint8 raw NRRD, attached or detached (.nhdr): the datasets here (VTK 9.1's Debian
    vtkNrrdReader is the MPI one and fails without a controller)."""
    with open(path, "rb") as f:
        raw = f.read()
    end = raw.index(b"\n\n") if b"\n\n" in raw else len(raw)
    fields = {}
    for line in raw[:end].decode("latin-1").splitlines()[1:]:
        if line.startswith("#") or ":" not in line:
            continue
        key, value = line.split(":", 1)
        fields[key.strip()] = value.strip()
    if fields.get("type") not in ("uint8", "uint8_t", "uchar", "unsigned char"):
        raise SystemExit(f"{path}: only uint8 NRRD is read here, not {fields.get('type')}")
    if fields.get("encoding") != "raw":
        raise SystemExit(f"{path}: only raw NRRD is read here")
    dims = [int(v) for v in fields["sizes"].split()]
    spacing = [1.0, 1.0, 1.0]
    if "spacings" in fields:
        spacing = [float(v) for v in fields["spacings"].split()]
    elif "space directions" in fields:
        vectors = [[float(x) for x in v.split(",")]
                   for v in re.findall(r"\(([^)]*)\)", fields["space directions"])]
        spacing = [math.sqrt(sum(x * x for x in v)) for v in vectors]  # axis-aligned here
    count = dims[0] * dims[1] * dims[2]
    if "data file" in fields:
        with open(os.path.join(os.path.dirname(path), fields["data file"]), "rb") as f:
            payload = f.read()
    else:
        payload = raw[end + 2:]
    voxels = numpy.frombuffer(payload[:count], dtype=numpy.uint8)
    image = vtk.vtkImageData()
    image.SetDimensions(*dims)
    image.SetSpacing(*spacing)
    array = numpy_to_vtk(voxels, deep=True, array_type=vtk.VTK_UNSIGNED_CHAR)
    array.SetName("scalars")
    image.GetPointData().SetScalars(array)
    return image


def read_volume(path):
    if path.endswith(".vti"):
        reader = vtk.vtkXMLImageDataReader()
        reader.SetFileName(path)
        reader.Update()
        return reader.GetOutput()
    return read_nrrd(path)


def view_direction(azimuth_deg):
    """From the volume's centre to the eye (vsil's default camera, src/core/camera.cpp: the eye
    orbits the box centre at rotY(az)·rotX(-el)·(0, 0, d), +y up)."""
    az, el = math.radians(azimuth_deg), math.radians(ELEVATION_DEG)
    return (math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az))


def place_camera(camera, image, azimuth_deg):
    """vsil's default view: d = bounding-sphere radius / sin(fov/2)."""
    dims = image.GetDimensions()
    spacing = image.GetSpacing()
    origin = image.GetOrigin()
    centre = [origin[a] + 0.5 * (dims[a] - 1) * spacing[a] for a in range(3)]
    radius = 0.5 * math.sqrt(sum((dims[a] * spacing[a]) ** 2 for a in range(3)))
    distance = radius / math.sin(math.radians(FOV_Y_DEG) / 2)
    az, el = math.radians(azimuth_deg), math.radians(ELEVATION_DEG)
    direction = view_direction(azimuth_deg)
    up = (-math.sin(el) * math.sin(az), math.cos(el), -math.sin(el) * math.cos(az))
    camera.SetFocalPoint(*centre)
    camera.SetPosition(*[centre[a] + distance * direction[a] for a in range(3)])
    camera.SetViewUp(*up)
    camera.SetViewAngle(FOV_Y_DEG)


def vsil_step_world(image, azimuth_deg):
    """vsil's distance between slices in world units: one voxel along the view direction,
    anisotropic spacing counted (slicer.cpp planSlices: 1 / |d / spacing|)."""
    d = view_direction(azimuth_deg)
    spacing = image.GetSpacing()
    return 1.0 / math.sqrt(sum((d[a] / spacing[a]) ** 2 for a in range(3)))


def summary(ms):
    median = statistics.median(ms)
    return {
        "frames": len(ms),
        "ms_median": median,
        "ms_min": min(ms),
        "ms_max": max(ms),
        "fps": 1000.0 / median,
    }


def vtk_pipeline(volume_path, size, window):
    """The VTK scene; returns frame(azimuth_deg) -> RGBA pixels, a PNG writer and facts."""
    image = read_volume(volume_path)
    lo, hi = image.GetScalarRange()
    low, high = window

    mapper = vtk.vtkGPUVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.SetBlendModeToMaximumIntensity()
    mapper.SetAutoAdjustSampleDistances(False)
    mapper.SetImageSampleDistance(1.0)

    # vsil's window: black at LO, white from HI on; nothing at or below LO.
    colour = vtk.vtkColorTransferFunction()
    colour.AddRGBPoint(min(lo, low), 0.0, 0.0, 0.0)
    colour.AddRGBPoint(low, 0.0, 0.0, 0.0)
    colour.AddRGBPoint(high, 1.0, 1.0, 1.0)
    colour.AddRGBPoint(max(hi, high), 1.0, 1.0, 1.0)
    opacity = vtk.vtkPiecewiseFunction()
    opacity.AddPoint(min(lo, low), 0.0)
    opacity.AddPoint(low, 0.0)
    opacity.AddPoint(low + 1e-3 * (high - low), 1.0)
    opacity.AddPoint(max(hi, high), 1.0)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(colour)
    prop.SetScalarOpacity(opacity)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()

    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0, 0, 0)
    window_ = vtk.vtkRenderWindow()
    window_.SetOffScreenRendering(1)
    window_.SetSize(size, size)
    window_.AddRenderer(renderer)

    def frame(azimuth_deg):
        mapper.SetSampleDistance(vsil_step_world(image, azimuth_deg))
        place_camera(renderer.GetActiveCamera(), image, azimuth_deg)
        renderer.ResetCameraClippingRange()
        window_.Render()
        pixels = vtk.vtkUnsignedCharArray()
        window_.GetRGBACharPixelData(0, 0, size - 1, size - 1, 0, pixels)  # waits for the frame
        return pixels

    def write_png(path):  # the first timed view, outside any timed region
        frame(ORBIT_START_DEG)
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window_)
        grab.ReadFrontBufferOff()
        grab.Update()
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(path)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()

    frame(ORBIT_START_DEG)  # creates the context, so that it can report itself
    gl = {}
    for line in window_.ReportCapabilities().splitlines():
        for key in ("OpenGL vendor string", "OpenGL renderer string", "OpenGL version string"):
            if line.startswith(key):
                gl[key.split()[1]] = line.split(":", 1)[1].strip()
    facts = {"value_range": [lo, hi], "dims": list(image.GetDimensions()),
             "spacing": list(image.GetSpacing()),
             "sample_distance_first_view": vsil_step_world(image, ORBIT_START_DEG)}
    return frame, write_png, facts, gl


def measure_vtk(frame, frames, warmup):
    for _ in range(warmup):
        frame(ORBIT_START_DEG)
    ms = []
    for i in range(frames):
        start = time.perf_counter()
        pixels = frame(ORBIT_START_DEG + ORBIT_STEP_DEG * i)
        ms.append(1000.0 * (time.perf_counter() - start))
    lit = int((vtk_to_numpy(pixels).reshape(-1, 4)[:, :3].max(axis=1) > 0).sum())
    if lit == 0:
        raise SystemExit("VTK: the last frame shows nothing")
    row = summary(ms)
    row["lit_pixels_last_frame"] = lit
    return row


def measure_vsil(vsil, datasets, name, size, frames, warmup):
    """vsil's MIP and DEMIP rows of one dv1 run (the columns take turns frame by frame)."""
    with tempfile.TemporaryDirectory() as tmp:
        json_path = os.path.join(tmp, "dv1.json")
        command = [vsil, "bench", "--table", "dv1", "--only", name, "--datasets", datasets,
                   "--sizes", str(size), "--frames", str(frames), "--warmup", str(warmup),
                   "--json", json_path]
        subprocess.run(command, check=True, stdout=sys.stderr)
        with open(json_path) as f:
            document = json.load(f)
    rows = {}
    for technique in ("mip", "demip"):
        found = [r for r in document["rows"]
                 if r.get("technique") == technique and "missing" not in r]
        if len(found) != 1 or found[0].get("check") != "ok":
            raise SystemExit(f"vsil bench gave no checked {technique} row for {name}: "
                             f"{document['rows']}")
        rows[technique] = {k: found[0][k] for k in
                           ("frames", "ms_median", "ms_min", "ms_max", "fps", "slices", "check")}
        if technique == "demip":
            rows[technique]["ratio"] = found[0]["ratio"]  # to MIP, from paired frames
    return rows, document.get("machine")


def vsil_render(vsil, path, size, out_png, meta_json):
    subprocess.run([vsil, "render", path, "--technique", "mip", "--background", "#000000",
                    "--size", f"{size}x{size}", "--view", f"{ORBIT_START_DEG:g},{ELEVATION_DEG:g}",
                    "--out", out_png, "--meta-out", meta_json], check=True, stdout=sys.stderr)
    with open(meta_json) as f:
        return json.load(f)


def vsil_window(vsil, path):
    """vsil's default window for the volume (from the histogram), [LO, HI] in data units."""
    with tempfile.TemporaryDirectory() as tmp:
        meta = vsil_render(vsil, path, 64, os.path.join(tmp, "w.png"),
                           os.path.join(tmp, "w.json"))
    window = meta["parameters"]["window"]
    if isinstance(window, str):
        window = [float(v) for v in window.split(",")]
    return [float(window[0]), float(window[1])]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vsil", default="build/vsil", help="the vsil binary (default build/vsil)")
    parser.add_argument("--datasets", default="../shared/datasets")
    parser.add_argument("--only", default=",".join(DATASETS),
                        help="comma-separated dataset names (default: all five of dv1)")
    parser.add_argument("--size", type=int, default=512, help="square window side (default 512)")
    parser.add_argument("--frames", type=int, default=10, help="timed frames per block (default 10)")
    parser.add_argument("--warmup", type=int, default=2, help="untimed frames per block (default 2)")
    parser.add_argument("--rounds", type=int, default=3,
                        help="VTK and vsil blocks alternate this many times per dataset, so that "
                             "load from other processes falls on both alike (default 3)")
    parser.add_argument("--json", help="write the rows and the machine here")
    parser.add_argument("--images", help="folder for vtk_mip_NAME.png and vsil_mip_NAME.png "
                                         "(the first timed view, both over black)")
    args = parser.parse_args()
    names = [n for n in args.only.split(",") if n]
    for n in names:
        if n not in DATASETS:
            raise SystemExit(f"--only: unknown dataset '{n}' (known: {', '.join(DATASETS)})")
    if args.images:
        os.makedirs(args.images, exist_ok=True)

    machine = {
        "cores": os.cpu_count(),
        "LP_NUM_THREADS": os.environ["LP_NUM_THREADS"],
        "vtk": vtk.vtkVersion.GetVTKVersion(),
        "python": platform.python_version(),
        "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "load_average": [load_average()],
    }
    rows = []
    for name in names:
        path = os.path.join(args.datasets, DATASETS[name])
        window = vsil_window(args.vsil, path)
        frame, write_vtk_png, facts, gl = vtk_pipeline(path, args.size, window)
        machine["vtk_gl"] = gl
        blocks = {"vtk": [], "mip": [], "demip": []}
        for r in range(args.rounds):
            print(f"{name} round {r + 1}/{args.rounds}: VTK", file=sys.stderr)
            blocks["vtk"].append(measure_vtk(frame, args.frames, args.warmup))
            machine["load_average"].append(load_average())
            print(f"{name} round {r + 1}/{args.rounds}: vsil", file=sys.stderr)
            vsil_rows, machine["vsil"] = measure_vsil(args.vsil, args.datasets, name, args.size,
                                                      args.frames, args.warmup)
            blocks["mip"].append(vsil_rows["mip"])
            blocks["demip"].append(vsil_rows["demip"])
            machine["load_average"].append(load_average())
        if args.images:
            write_vtk_png(os.path.join(args.images, f"vtk_mip_{name}.png"))
            with tempfile.TemporaryDirectory() as tmp:
                vsil_render(args.vsil, path, args.size,
                            os.path.join(args.images, f"vsil_mip_{name}.png"),
                            os.path.join(tmp, "meta.json"))
        row = {"table": "vtk-peer", "dataset": name, "width": args.size, "height": args.size,
               "window": window, **facts}
        for key, block in blocks.items():
            medians = [b["ms_median"] for b in block]
            row[key] = {"ms_median": statistics.median(medians), "round_ms_medians": medians,
                        "frames": sum(b["frames"] for b in block), "rounds": block}
        row["vtk_over_vsil_mip"] = row["vtk"]["ms_median"] / row["mip"]["ms_median"]
        # Per round, from the same dv1 frames: DEMIP's frame over MIP's in the same turn, the
        # median over the round's frames (the dv1 row's paired "ratio"); overall their median.
        row["demip_over_mip_rounds"] = [d["ratio"] for d in blocks["demip"]]
        row["demip_over_mip"] = statistics.median(row["demip_over_mip_rounds"])
        rows.append(row)
        del frame, write_vtk_png

    wins = sum(1 for r in rows if r["vtk_over_vsil_mip"] > 1.0)
    print(f"VTK {machine['vtk']} ({machine.get('vtk_gl', {}).get('renderer', '?')}), "
          f"LP_NUM_THREADS={machine['LP_NUM_THREADS']}, {machine['cores']} cores, "
          f"{machine['date']}; load average (1, 5, 15 min) at start and after each block: "
          + " | ".join(machine["load_average"]))
    print("| dataset | window | VTK MIP ms (round medians) | vsil MIP ms (round medians) | "
          "VTK/vsil | vsil DEMIP ms | DEMIP/MIP (rounds) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        def cell(key):
            rounds_ = ", ".join(f"{m:.0f}" for m in r[key]["round_ms_medians"])
            return f"{r[key]['ms_median']:.0f} ({rounds_})"
        dims = "×".join(str(d) for d in r["dims"])
        ratios = ", ".join(f"{x:.2f}" for x in r["demip_over_mip_rounds"])
        print(f"| {r['dataset']} {dims} | {r['window'][0]:g}..{r['window'][1]:g} | "
              f"{cell('vtk')} | {cell('mip')} | {r['vtk_over_vsil_mip']:.2f} | "
              f"{r['demip']['ms_median']:.0f} | {r['demip_over_mip']:.2f} ({ratios}) |")
    print(f"vsil's MIP faster than VTK's on {wins} of {len(rows)} datasets "
          f"(VTK/vsil > 1 in frame time); {args.size}², {args.frames} timed frames per block")
    document = {"machine": machine, "rows": rows, "vsil_faster_on": wins}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(document, f, indent=2)
            f.write("\n")
    else:
        print(json.dumps(document, indent=2))


if __name__ == "__main__":
    main()
