// hit_records.glsl: what the techniques that look for the iso-surface's first hit share
// (silhouette, rightangle, firsthit): the pixel states and the per-pixel record
// (slicing/hit_records.h).
// Pixel states, equal to vsil::PixelState (src/core/frame.h; a GL test checks they agree).
#define STATE_EMPTY 0u
#define STATE_FILLED 1u
#define STATE_CONTOUR 2u
#define STATE_SILHOUETTE 3u

uniform float isoValue;  // in data units

// Records t = (state, depth, first-hit eye distance, a technique's own value): depth is the
// normalized depth of what the pixel shows, the eye distance where finish_hits.frag shades it.
// Shading runs once per pixel after the last slice: llvmpipe runs both sides of a branch, so a
// per-slice gradient would cost every pixel of every slice.

// FILLED and SILHOUETTE never change again.
bool isFinal(uint state) { return state == STATE_FILLED || state == STATE_SILHOUETTE; }
