// rightangle.glsl: the right-angle line test for finish_hits.frag. A first hit is a line pixel
// where (1 - |n·v|)^rightAngleExponent > rightAngleThreshold.
uniform float rightAngleExponent;
uniform float rightAngleThreshold;

uint finishState(vec4 record, float shade, inout float depth) {
  uint state = uint(record.r);
  if (state != STATE_EMPTY && pow(1.0 - shade, rightAngleExponent) > rightAngleThreshold) {
    state = STATE_SILHOUETTE;
  }
  return state;
}
