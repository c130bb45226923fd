#!/usr/bin/python3
"""Peer measurement: VTK's GPU volume mapper in MIP mode beside vsil's MIP, in one run.

Issue 11 (Benchmark) asks for VTK's GPU ray caster in maximum-intensity mode measured beside
vsil's `mip` once, on the Bonsai (256³) at 512², on the same machine and in the same run.
This script times both and prints a table and JSON like the `vsil bench` tables.

It is a one-off peer measurement, not part of CI or bootstrap. Needs Debian's VTK bindings and
a virtual X server (VTK 9.1 in bookworm renders through GLX):

    apt-get install -y python3-vtk9 xvfb xauth
    xvfb-run -a -s "-screen 0 1024x768x24" /usr/bin/python3 bench/peers/vtk_mip.py \
        --vsil build/vsil --json vtk_mip.json --images .

Both sides render on Mesa's llvmpipe with LP_NUM_THREADS threads (2 unless already set; on a
2-core machine that is llvmpipe's default, one thread per core). What is compared:

- VTK: vtkGPUVolumeRayCastMapper, MaximumIntensityBlend, a grey ramp over the value range
  (black..white; opacity 0 at the minimum, 1 just above it, so values at the minimum show
  nothing, as vsil's default --window), one sample per voxel (sample distance = the smallest
  spacing, no automatic adjustment), image sample distance 1, 512×512 offscreen window.
  Timed per frame: Render() and a readback of the RGBA pixels (the readback waits for the
  frame to finish).
- vsil: `vsil bench --table dv1 --only bonsai` (its MIP column; the table's other columns take
  turns with it frame by frame). Timed per frame in-process: Renderer::render (slicing,
  glFinish, readback).
- The same orbit as the dv1 table: warm-up frames from azimuth 30°, elevation 20°; timed frame
  i from azimuth 30° + 3.6°·i, elevation 20°; perspective, 30° vertical field of view, the
  volume's bounding sphere filling the window (vsil's default camera, src/core/camera.cpp).
- VTK and vsil blocks (warm-up + timed frames each) alternate --rounds times, so that load from
  other processes falls on both alike. Reported: per renderer the median of its blocks' median
  frame times, fps = 1000 / that, each block's median, min and max, and VTK/vsil in frame time;
  the load average at the start and after every block.
"""

import argparse
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("LP_NUM_THREADS", "2")  # before VTK loads Mesa

import vtk  # noqa: E402  (Debian: python3-vtk9)
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

ORBIT_START_DEG, ORBIT_STEP_DEG, ELEVATION_DEG = 30.0, 3.6, 20.0  # dv1's orbit
FOV_Y_DEG = 30.0  # vsil's default perspective


def load_average():
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def place_camera(camera, image, azimuth_deg):
    """vsil's default view (src/core/camera.cpp): the eye orbits the box centre at
    rotY(az)·rotX(-el)·(0, 0, d), d = bounding-sphere radius / sin(fov/2), +y up."""
    dims = image.GetDimensions()
    spacing = image.GetSpacing()
    origin = image.GetOrigin()
    centre = [origin[a] + 0.5 * (dims[a] - 1) * spacing[a] for a in range(3)]
    radius = 0.5 * math.sqrt(sum((dims[a] * spacing[a]) ** 2 for a in range(3)))
    distance = radius / math.sin(math.radians(FOV_Y_DEG) / 2)
    az, el = math.radians(azimuth_deg), math.radians(ELEVATION_DEG)
    direction = (math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az))
    up = (-math.sin(el) * math.sin(az), math.cos(el), -math.sin(el) * math.cos(az))
    camera.SetFocalPoint(*centre)
    camera.SetPosition(*[centre[a] + distance * direction[a] for a in range(3)])
    camera.SetViewUp(*up)
    camera.SetViewAngle(FOV_Y_DEG)


def summary(ms):
    median = statistics.median(ms)
    return {
        "frames": len(ms),
        "ms_median": median,
        "ms_min": min(ms),
        "ms_max": max(ms),
        "fps": 1000.0 / median,
    }


def vtk_pipeline(volume_path, size):
    """The VTK scene; returns frame(azimuth_deg) -> RGBA pixels, a PNG writer and facts."""
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(volume_path)
    reader.Update()
    image = reader.GetOutput()
    lo, hi = image.GetScalarRange()

    mapper = vtk.vtkGPUVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.SetBlendModeToMaximumIntensity()
    mapper.SetAutoAdjustSampleDistances(False)
    mapper.SetSampleDistance(min(image.GetSpacing()))  # one sample per voxel, like vsil's 1 slice
    mapper.SetImageSampleDistance(1.0)

    colour = vtk.vtkColorTransferFunction()
    colour.AddRGBPoint(lo, 0.0, 0.0, 0.0)
    colour.AddRGBPoint(hi, 1.0, 1.0, 1.0)
    opacity = vtk.vtkPiecewiseFunction()
    opacity.AddPoint(lo, 0.0)
    opacity.AddPoint(lo + 1e-3 * (hi - lo), 1.0)
    opacity.AddPoint(hi, 1.0)
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
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)

    def frame(azimuth_deg):
        place_camera(renderer.GetActiveCamera(), image, azimuth_deg)
        renderer.ResetCameraClippingRange()
        window.Render()
        pixels = vtk.vtkUnsignedCharArray()
        window.GetRGBACharPixelData(0, 0, size - 1, size - 1, 0, pixels)  # waits for the frame
        return pixels

    def write_png(path):  # the first timed view, outside any timed region
        frame(ORBIT_START_DEG)
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.ReadFrontBufferOff()
        grab.Update()
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(path)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()

    frame(ORBIT_START_DEG)  # creates the context, so that it can report itself
    gl = {}
    for line in window.ReportCapabilities().splitlines():
        for key in ("OpenGL vendor string", "OpenGL renderer string", "OpenGL version string"):
            if line.startswith(key):
                gl[key.split()[1]] = line.split(":", 1)[1].strip()
    facts = {"gl": gl, "value_range": [lo, hi], "sample_distance": mapper.GetSampleDistance()}
    return frame, write_png, facts


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


def measure_vsil(vsil, datasets, size, frames, warmup):
    with tempfile.TemporaryDirectory() as tmp:
        json_path = os.path.join(tmp, "dv1.json")
        command = [vsil, "bench", "--table", "dv1", "--only", "bonsai", "--datasets", datasets,
                   "--sizes", str(size), "--frames", str(frames), "--warmup", str(warmup),
                   "--json", json_path]
        subprocess.run(command, check=True, stdout=sys.stderr)
        with open(json_path) as f:
            document = json.load(f)
    mip = [r for r in document["rows"] if r.get("technique") == "mip" and "missing" not in r]
    if len(mip) != 1 or mip[0].get("check") != "ok":
        raise SystemExit(f"vsil bench gave no checked MIP row for bonsai: {document['rows']}")
    row = {k: mip[0][k] for k in ("frames", "ms_median", "ms_min", "ms_max", "fps", "check")}
    return row, document.get("machine")


def write_vsil_png(vsil, datasets, size, path):
    subprocess.run([vsil, "render", os.path.join(datasets, "bonsai.vti"), "--technique", "mip",
                    "--size", f"{size}x{size}", "--view", f"{ORBIT_START_DEG:g},{ELEVATION_DEG:g}",
                    "--out", path], check=True, stdout=sys.stderr)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vsil", default="build/vsil", help="the vsil binary (default build/vsil)")
    parser.add_argument("--datasets", default="../shared/datasets")
    parser.add_argument("--size", type=int, default=512, help="square window side (default 512)")
    parser.add_argument("--frames", type=int, default=10, help="timed frames per block (default 10)")
    parser.add_argument("--warmup", type=int, default=2, help="untimed frames per block (default 2)")
    parser.add_argument("--rounds", type=int, default=3,
                        help="VTK and vsil blocks alternate this many times, so that load from "
                             "other processes falls on both alike (default 3)")
    parser.add_argument("--json", help="write the rows and the machine here")
    parser.add_argument("--images", help="folder for vtk_mip_bonsai.png and vsil_mip_bonsai.png")
    args = parser.parse_args()

    machine = {
        "cores": os.cpu_count(),
        "LP_NUM_THREADS": os.environ["LP_NUM_THREADS"],
        "vtk": vtk.vtkVersion.GetVTKVersion(),
        "python": platform.python_version(),
        "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "load_average": [load_average()],
    }
    frame, write_vtk_png, facts = vtk_pipeline(os.path.join(args.datasets, "bonsai.vti"), args.size)
    machine["vtk_gl"] = facts.pop("gl")
    rounds = {"vtk": [], "vsil": []}
    for r in range(args.rounds):
        print(f"round {r + 1}/{args.rounds}: VTK", file=sys.stderr)
        rounds["vtk"].append(measure_vtk(frame, args.frames, args.warmup))
        machine["load_average"].append(load_average())
        print(f"round {r + 1}/{args.rounds}: vsil", file=sys.stderr)
        row, machine["vsil"] = measure_vsil(args.vsil, args.datasets, args.size, args.frames,
                                            args.warmup)
        rounds["vsil"].append(row)
        machine["load_average"].append(load_average())
    if args.images:
        write_vtk_png(os.path.join(args.images, "vtk_mip_bonsai.png"))
        write_vsil_png(args.vsil, args.datasets, args.size,
                       os.path.join(args.images, "vsil_mip_bonsai.png"))

    rows = []
    for name in ("vtk", "vsil"):
        medians = [b["ms_median"] for b in rounds[name]]
        median = statistics.median(medians)
        rows.append({"table": "vtk-peer", "dataset": "bonsai", "width": args.size,
                     "height": args.size, "technique": "mip", "renderer": name,
                     "frames": sum(b["frames"] for b in rounds[name]), "ms_median": median,
                     "fps": 1000.0 / median, "round_ms_medians": medians,
                     "rounds": rounds[name], **(facts if name == "vtk" else {})})
    ratio = rows[0]["ms_median"] / rows[1]["ms_median"]

    print(f"VTK {machine['vtk']} ({machine['vtk_gl'].get('renderer', '?')}), "
          f"LP_NUM_THREADS={machine['LP_NUM_THREADS']}, {machine['cores']} cores, "
          f"{machine['date']}; load average (1, 5, 15 min) at start and after each block: "
          + " | ".join(machine["load_average"]))
    print("| dataset | window | renderer | frames | ms/frame (median of rounds) | "
          "round medians (ms) | fps |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        round_ms = ", ".join(f"{m:.0f}" for m in r["round_ms_medians"])
        print(f"| bonsai 256³ | {args.size}² | {r['renderer']} MIP | {r['frames']} | "
              f"{r['ms_median']:.0f} | {round_ms} | {r['fps']:.2f} |")
    print(f"VTK/vsil frame time: {ratio:.2f} ({'vsil' if ratio > 1 else 'VTK'} is faster)")
    document = {"machine": machine, "rows": rows, "vtk_over_vsil_ms": ratio}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(document, f, indent=2)
            f.write("\n")
    else:
        print(json.dumps(document, indent=2))


if __name__ == "__main__":
    main()
