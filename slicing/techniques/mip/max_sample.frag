// max_sample.frag (mip and demip, per slice): the sample this pixel sees on this slice. MAX
// blending keeps each pixel's maximum over the slices (order-independent), in an R32F target
// cleared to kNoSample (mip_technique.h). The depth test (GREATER, no writes) skips pixels in
// front of the first occupied brick and rays that meet none (empty_space.h).
// Out: the sample value, data units.
layout(location = 0) out float result;

void main() {
  vec3 voxel = sliceVoxel();
  if (!insideVolume(voxel)) discard;
  result = sampleVolume(voxel);
}
