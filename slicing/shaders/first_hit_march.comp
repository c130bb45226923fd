// first_hit_march.comp (tiles pipeline of the first-hit techniques; slicing/hit_records.h): each
// pixel's first sample at or above the iso value, front to back; one invocation per pixel of a
// MARCH_TILE_X x MARCH_TILE_Y tile (shaders/tile_march.glsl), no apron: no pixel reads another's
// samples, so the loop has no barrier. Each invocation starts at the first slice beyond where
// its ray enters occupied bricks and stops at its first hit or where its ray leaves them for
// good; llvmpipe runs 8 invocations at a time until all 8 are done.
// Out: the record (STATE_FILLED, depth, first-hit eye distance, 1) at hits, 0 elsewhere, as
// first_hit.frag leaves it.
layout(local_size_x = MARCH_TILE_X, local_size_y = MARCH_TILE_Y) in;

void main() {
  ivec2 pixel = tileOrigin() + ivec2(gl_LocalInvocationID.xy);
  bool inImage = insideImage(pixel);
  vec4 record = vec4(0.0);
  if (continuesMarch() && inImage) record = imageLoad(recordImage, pixel);
  float entryDepth = inImage ? entryDepthAt(pixel) : 1.0;
  float exitDepth = inImage && record.a == 0.0 ? exitDepthAt(pixel) : 0.0;
  // Slice parameters are gathered lane by lane anyway, so each pixel may start at its own slice.
  int first = firstSliceBeyond(tileFirstSlice(entryDepth), entryDepth);
  vec2 ndc = pixelNdc(pixel);
  for (int k = first; k < rangeEndSlice; ++k) {
    SliceParams slice = sliceAt(k);
    if (slice.windowDepth >= exitDepth) break;
    vec3 voxel = sliceVoxelOf(slice, ndc);
    if (insideVolume(voxel) && sampleVolume(voxel) >= isoValue) {
      record = vec4(float(STATE_FILLED), slice.depth, slice.eyeDistance, 1.0);
      break;
    }
  }
  if (inImage) imageStore(recordImage, pixel, record);
}
