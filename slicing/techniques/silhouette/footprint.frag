// footprint.frag (silhouette, both pipelines): the alpha test of the slice.
// In: the volume on this slice. Out: footprint = footprintTag() where the sample is >= isoValue
// (FILLED); other pixels are discarded and keep an older tag or the cleared 0 (EMPTY).
layout(location = 0) out uint footprint;

void main() {
  vec3 voxel = sliceVoxel();
  if (!insideVolume(voxel) || sampleVolume(voxel) < isoValue) discard;
  footprint = footprintTag();
}
