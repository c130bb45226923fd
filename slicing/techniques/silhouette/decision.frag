// decision.frag (paper pipeline, pass 3 of 3): Nagy–Klein's decision table.
// In: the record t (silhouette.glsl) from the slices in front; this slice's contour value c
//     (EMPTY, FILLED or CONTOUR), or EMPTY everywhere with EMPTY_SLICE (the extra slice behind
//     the volume).
// Out: t' (decideRecord in silhouette.glsl), written to the other ping-pong target.
layout(binding = UNIT_CONTOUR) uniform usampler2D contourTexture;
layout(binding = UNIT_RECORD) uniform sampler2D recordTexture;
layout(location = 0) out vec4 result;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef EMPTY_SLICE
  uint c = STATE_EMPTY;
#else
  uint c = texelFetch(contourTexture, pixel, 0).r;
#endif
  result = decideRecord(texelFetch(recordTexture, pixel, 0), c);
}
