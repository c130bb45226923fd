// decision_inplace.frag (fast pipeline, pass 2 of 2): contour and decision table fused, the
// intermediate record updated in place.
// In:  footprintTexture (0 EMPTY, 1 FILLED) of this slice; emptySlice != 0 for the extra
//      slice behind the volume (every c EMPTY).
// In/out: the intermediate record t = (state, depth, shade, 0), read through
//      intermediateTexture and written through intermediateImage (the same texture). Each pixel
//      reads and writes only its own record, so no ping-pong is needed, and only records that
//      change are stored; FILLED and SILHOUETTE pixels are final and cost one fetch. (Reads go
//      through the sampler because llvmpipe's imageLoad costs ten times a texelFetch; a
//      texture-fetch barrier between slices makes the stores visible.) No colour output.
uniform sampler2D intermediateTexture;
layout(rgba32f) uniform writeonly restrict image2D intermediateImage;
uniform usampler2D footprintTexture;
uniform int emptySlice;
uniform float previousSliceDepth;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 t = texelFetch(intermediateTexture, pixel, 0);
  uint state = uint(t.r);
  if (isFinal(state)) return;
  uint c = emptySlice != 0 ? STATE_EMPTY : contourAt(footprintTexture, pixel);
  if (decide(state, c) == state) return;  // EMPTY stays EMPTY, CONTOUR propagates
  imageStore(intermediateImage, pixel, decideRecord(t, c, previousSliceDepth));
}
