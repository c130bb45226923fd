// march.comp: illustrate's tile march (`--pipeline tiles`; slicing/tile_march.h), one invocation
// per pixel of a MARCH_TILE_X x MARCH_TILE_Y tile, no apron. Each invocation composites its
// pixel's samples front to back in a register, on slice after slice and exactly where the slice
// pass samples them (boxAlignedVoxel, illustrate_sample.glsl with SKIP_SAMPLE `return false`):
// from the first slice beyond where its ray enters occupied bricks until its samples lie past
// where it leaves them for good or, with early ray termination, to the end of the first group
// of kMarkDeadInterval slices after which its opacity reached deadOpacity (where the slice
// pass's mark_dead.frag retires the pixel), so that both pipelines composite the same samples.
// Out: the premultiplied (c·α, α) as the slice pass's blending leaves it.
layout(local_size_x = MARCH_TILE_X, local_size_y = MARCH_TILE_Y) in;

uniform float deadOpacity;

// Slice k samples between the planes of slices k − 1 and k (boxAlignedVoxel): past the exit once
// the plane of k − 1 is, where it and every later sample add nothing (mark_dead.frag's rule,
// which retires a pixel once its slice's plane is past the exit, relies on the same).
bool pastExit(int k, float exitDepth) {
  return k > rangeFirstSlice && sliceWindowDepthAt(k - 1) >= exitDepth;
}

void main() {
  ivec2 pixel = tileOrigin() + ivec2(gl_LocalInvocationID.xy);
  bool inImage = insideImage(pixel);
  // A march over several dispatches continues the colour the previous one left.
  vec4 accumulated = vec4(0.0);
  if (continuesMarch() && inImage) accumulated = imageLoad(recordImage, pixel);
  float entryDepth = inImage ? entryDepthAt(pixel) : 1.0;
  float exitDepth = inImage ? exitDepthAt(pixel) : 0.0;
  int first = firstSliceBeyond(tileFirstSlice(entryDepth), entryDepth);
  if (accumulated.a >= deadOpacity) first = rangeEndSlice;
  vec2 ndc = pixelNdc(pixel);
  PixelRay ray = pixelRay(pixelCentre(pixel));
  float phase = boxPhase(ray);
  // The ray's leading samples that add nothing, passed over with addsNothing's cheaper test:
  // llvmpipe runs 8 invocations in lockstep and pays a branch's both sides for all of them, so
  // in the loop below a transparent sample costs as much as a shaded one. Skipped samples leave
  // the colour as it is, so the loop below composites what it would have.
  for (; first < rangeEndSlice; ++first) {
    if (pastExit(first, exitDepth)) break;
    vec3 voxel = boxAlignedVoxel(ray, phase, first);
    if (insideVolume(voxel) && !addsNothing(voxel)) break;
  }
  for (int k = first; k < rangeEndSlice; ++k) {
    if (pastExit(k, exitDepth)) break;
    vec3 voxel = boxAlignedVoxel(ray, phase, k);
    vec4 premultiplied;
    if (insideVolume(voxel) &&
        illustratedSample(voxel, ndc, sliceEyeDistanceAt(k), sliceDepthAt(k), premultiplied)) {
      // The slice pass's blending (ONE_MINUS_DST_ALPHA, ONE), operation for operation.
      accumulated = premultiplied * (1.0 - accumulated.a) + accumulated;
    }
    // Early ray termination where mark_dead.frag retires the pixel: at the end of each group.
    if (k % MARK_DEAD_INTERVAL == MARK_DEAD_INTERVAL - 1 && accumulated.a >= deadOpacity) break;
  }
  if (inImage) imageStore(recordImage, pixel, accumulated);
}
