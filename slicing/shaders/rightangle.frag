// rightangle.frag: the right-angle baseline (RA). One pass per slice, depth test LESS, so the
// first iso-surface hit along each ray wins. Out: (state, depth, shade, 0) with state
// STATE_SILHOUETTE where (1 - |n·v|)^rightAngleExponent > rightAngleThreshold, else STATE_FILLED.
uniform float rightAngleExponent;
uniform float rightAngleThreshold;
layout(location = 0) out vec4 result;

void main() {
  vec3 eye = slicePointEye();
  vec3 voxel = voxelFromEyePoint(eye);
  if (!insideVolume(voxel) || sampleVolume(voxel) < isoValue) discard;
  float facing = facingRatio(voxel, eye);
  bool line = pow(1.0 - facing, rightAngleExponent) > rightAngleThreshold;
  result = vec4(float(line ? STATE_SILHOUETTE : STATE_FILLED), sliceDepth, facing, 0.0);
}
