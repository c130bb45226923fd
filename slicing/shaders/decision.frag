// decision.frag (paper pipeline, pass 3 of 3): Nagy–Klein's decision table.
// In: intermediateTexture t (the record, common.glsl) from the slices in front;
//     contourTexture c (EMPTY, FILLED or CONTOUR) of this slice, or EMPTY everywhere when
//     emptySlice != 0 (the extra slice behind the volume).
// Out: t' (decideRecord in common.glsl), written to the other ping-pong target.
uniform usampler2D contourTexture;
uniform sampler2D intermediateTexture;
uniform int emptySlice;
layout(location = 0) out vec4 result;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  uint c = emptySlice != 0 ? STATE_EMPTY : texelFetch(contourTexture, pixel, 0).r;
  result = decideRecord(texelFetch(intermediateTexture, pixel, 0), c);
}
