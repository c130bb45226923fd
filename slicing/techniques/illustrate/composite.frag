// composite.frag: illustrate's slice pass (illustrate_technique.h), the `fast` pipeline: this
// slice's sample of the pixel (illustrate_sample.glsl, SKIP_SAMPLE discard), written
// premultiplied for the front-to-back blending (slicing/compositing.h).
// Out: (c·α, α).

layout(location = 0) out vec4 result;

void main() {
  vec3 voxel = sliceVoxel();
  // The pieces overlap across brick borders (slicer.h slicePieces): the owner draws a sample.
  if (!insideVolume(voxel) || !ownedByBrick(voxel)) discard;
  illustratedSample(voxel, fragmentNdc(), sliceEyeDistance, sliceDepth, result);
}
