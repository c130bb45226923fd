// decision.frag (silhouette pass 3 of 3): Nagy–Klein's decision table.
// In: intermediateTexture t = (state, depth, shade, 0) from the slices in front;
//     contourTexture c (EMPTY, FILLED or CONTOUR) of this slice, or EMPTY everywhere when
//     emptySlice != 0 (the extra slice behind the volume).
// Out: t' = (table[t][c], depth, shade, 0), written to the other ping-pong target.
// depth: for FILLED the first hit's normalized depth; for SILHOUETTE the middle of the run of
// CONTOUR samples that ended in the detection, where the view ray grazes the surface.
uniform usampler2D contourTexture;
uniform sampler2D intermediateTexture;
uniform int emptySlice;
uniform float previousSliceDepth;
layout(location = 0) out vec4 result;

// Rows t, columns c (EMPTY, FILLED, CONTOUR, and SILHOUETTE, which c never is).
const uint decisionTable[16] = uint[16](
    STATE_EMPTY, STATE_FILLED, STATE_CONTOUR, STATE_EMPTY,                    // t = EMPTY
    STATE_FILLED, STATE_FILLED, STATE_FILLED, STATE_FILLED,                   // t = FILLED
    STATE_SILHOUETTE, STATE_FILLED, STATE_CONTOUR, STATE_CONTOUR,             // t = CONTOUR
    STATE_SILHOUETTE, STATE_SILHOUETTE, STATE_SILHOUETTE, STATE_SILHOUETTE);  // t = SILHOUETTE

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 t = texelFetch(intermediateTexture, pixel, 0);
  uint state = uint(t.r);
  uint c = emptySlice != 0 ? STATE_EMPTY : texelFetch(contourTexture, pixel, 0).r;
  uint next = decisionTable[state * 4u + c];
  result = vec4(float(next), t.g, t.b, 0.0);
  if (state == STATE_EMPTY && next != STATE_EMPTY) {
    vec3 eye = slicePointEye();
    result.g = sliceDepth;
    result.b = facingRatio(voxelFromEyePoint(eye), eye);
  } else if (state == STATE_CONTOUR && next == STATE_SILHOUETTE) {
    result.g = 0.5 * (t.g + previousSliceDepth);
  }
}
