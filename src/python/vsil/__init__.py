"""vsil: volume illustration (exact silhouettes, Ebert-Rheingans, DEMIP) rendered offscreen.

    import vsil
    volume = vsil.load("bonsai.vti")            # or vsil.Volume(ndarray), vsil.generate(...)
    with vsil.Renderer() as renderer:           # one GL context, reused by every render
        frame = renderer.render(volume, iso=40, width_near=4, width_far=1)
    frame.image, frame.state, frame.depth, frame.metadata
"""
from ._vsil import (Frame, Renderer, Volume, __version__, broaden, generate, load,
                    measure_width)

__all__ = ["Frame", "Renderer", "Volume", "__version__", "broaden", "generate", "load",
           "measure_width"]
