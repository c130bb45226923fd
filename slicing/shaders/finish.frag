// finish.frag: once per frame, after the last slice. Shades the first hit of every pixel.
// In: recordTexture (the record, common.glsl). A CONTOUR record left by the fast pipeline met
// the extra empty slice behind the volume and becomes SILHOUETTE (decision_inplace.frag).
// Out: (state, depth, shade, 0), shade = |n·v| at the first hit (0 for EMPTY pixels).
// With RIGHT_ANGLE_LINES defined (the rightangle technique, whose records hold STATE_FILLED for
// every hit) a hit becomes STATE_SILHOUETTE where (1 - |n·v|)^rightAngleExponent >
// rightAngleThreshold.
uniform sampler2D recordTexture;
uniform float rightAngleExponent;
uniform float rightAngleThreshold;
layout(location = 0) out vec4 result;

void main() {
  vec4 record = texelFetch(recordTexture, ivec2(gl_FragCoord.xy), 0);
  uint state = uint(record.r);
  float depth = record.g;
  if (state == STATE_CONTOUR) {
    state = STATE_SILHOUETTE;
    depth = silhouetteDepth(record);
  }
  float shade = 0.0;
  if (state != STATE_EMPTY) {
    vec3 eye = eyePointAt(record.b);
    shade = facingRatio(voxelFromEyePoint(eye), eye);
#ifdef RIGHT_ANGLE_LINES
    if (pow(1.0 - shade, rightAngleExponent) > rightAngleThreshold) state = STATE_SILHOUETTE;
#endif
  }
  result = vec4(float(state), depth, shade, 0.0);
}
