// rightangle.frag: the right-angle baseline (RA), one pass per slice, front to back, with the
// depth test (LESS) keeping the first iso-surface hit along each ray: slices come in depth
// order, so pixels with a hit reject later slices' fragments before any sampling.
// Out: the record (STATE_FILLED, depth, first-hit eye distance, 0); finish.frag
// (RIGHT_ANGLE_LINES) then applies the line test once per pixel.
layout(location = 0) out vec4 result;

void main() {
  vec3 voxel = voxelFromEyePoint(slicePointEye());
  if (!insideVolume(voxel) || sampleVolume(voxel) < isoValue) discard;
  result = vec4(float(STATE_FILLED), sliceDepth, sliceEyeDistance, 0.0);
}
