// rightangle.frag: the right-angle baseline (RA), one pass per slice, front to back.
// In/out: the record (state, depth, first-hit eye distance, 0), read through resultTexture and
// written through resultImage (the same texture), updated in place: the first iso-surface hit
// along each ray is stored as STATE_FILLED; finish.frag (RIGHT_ANGLE_LINES) then applies the
// line test once per pixel. No colour output.
uniform sampler2D resultTexture;
layout(rgba32f) uniform writeonly restrict image2D resultImage;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (texelFetch(resultTexture, pixel, 0).r != float(STATE_EMPTY)) return;
  vec3 voxel = voxelFromEyePoint(slicePointEye());
  if (!insideVolume(voxel) || sampleVolume(voxel) < isoValue) return;
  imageStore(resultImage, pixel, vec4(float(STATE_FILLED), sliceDepth, sliceEyeDistance, 0.0));
}
