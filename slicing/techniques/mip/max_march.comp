// max_march.comp (mip and demip when the volume is one texture; mip_technique.h): each pixel's
// maximum over the slices and, with DEMIP, the first sample of its material, in one compute
// dispatch (shaders/tile_march.glsl): one invocation per pixel of a MARCH_TILE_X x MARCH_TILE_Y
// tile, sampling exactly where max_sample.frag and first_hit.frag do, on the slices beyond
// where its ray enters occupied bricks (the slice passes' GREATER test) up to where it leaves
// them for good (tile_march.glsl sliceSpan; past there every sample lies in bricks that cannot
// hold a shown maximum: mip_technique.cpp occupancy).
// DEMIP: a second loop finds the first sample within materialEps of the maximum M, from a bound
// the first loop keeps on where it can be. That hit is a record (a sample above every one
// before it: those lie below M - eps, it does not), so it lies in a run of consecutive records;
// before a run starts every sample is at most the maximum then. The first loop keeps the starts
// of the latest three runs and the maximum before each: the latest start whose maximum before
// it is below M - eps bounds the hit (the hit lies in that run or a later one). A record that
// rises more than eps above the maximum before it bounds it too (every earlier sample is below
// M - eps), for rays with more runs near the top. The second loop then walks about the hit's
// run's rise instead of the ray up to it (bonsai, 512²: 3.4 samples per 8 lanes, against 15.9
// with the one candidate kept before and 79 in the first loop).
// Out: the record (maximum, normalized depth d of the hit, its eye distance, 1; no hit: 0, 0,
// 0): mip_finish.frag reads the maximum from .r and the hit from .g and .b, where
// hit_records.glsl keeps them; noSample (kNoSample) where no slice sampled the pixel.
layout(local_size_x = MARCH_TILE_X, local_size_y = MARCH_TILE_Y) in;

uniform float noSample;
#ifdef DEMIP
uniform float materialEps;
#endif

void main() {
  ivec2 pixel = tileOrigin() + ivec2(gl_LocalInvocationID.xy);
  bool inImage = insideImage(pixel);
  float entryDepth = inImage ? entryDepthAt(pixel) : 1.0;
  float exitDepth = inImage ? exitDepthAt(pixel) : 0.0;
  // The lanes search from the tile's first slice (every invocation calls it: barriers).
  SliceSpan span = sliceSpan(tileFirstSlice(entryDepth), entryDepth, exitDepth);
  PixelRay ray = pixelRay(pixelCentre(pixel));
  float maximum = noSample;
#ifdef DEMIP
  int jumpBound = span.first;              // the last record more than eps above all before it
  bool previousWasRecord = false;
  ivec3 runStart = ivec3(span.first);      // of the latest three runs of records, oldest first
  vec3 maximumBeforeRun = vec3(noSample);  // the maximum of the samples before each
#endif
  for (int k = span.first; k < span.end; ++k) {
    vec3 voxel = rayVoxel(ray, k);
    if (insideVolume(voxel)) {
      float value = sampleVolume(voxel);
#ifdef DEMIP
      bool isRecord = value > maximum;
      if (isRecord && !previousWasRecord) {
        runStart = ivec3(runStart.yz, k);
        maximumBeforeRun = vec3(maximumBeforeRun.yz, maximum);
      }
      if (value - materialEps > maximum) jumpBound = k;
      previousWasRecord = isRecord;
#endif
      maximum = max(maximum, value);
    }
  }
  vec4 record = vec4(maximum, 0.0, 0.0, 0.0);
#ifdef DEMIP
  float threshold = maximum - materialEps;
  int hitLowerBound = jumpBound;  // no slice before it holds the hit
  if (maximumBeforeRun.z < threshold) {
    hitLowerBound = max(hitLowerBound, runStart.z);
  } else if (maximumBeforeRun.y < threshold) {
    hitLowerBound = max(hitLowerBound, runStart.y);
  } else if (maximumBeforeRun.x < threshold) {
    hitLowerBound = max(hitLowerBound, runStart.x);
  }
  int hit = span.end;
  for (int k = hitLowerBound; k < span.end; ++k) {
    vec3 voxel = rayVoxel(ray, k);
    if (insideVolume(voxel) && sampleVolume(voxel) >= threshold) {
      hit = k;
      break;
    }
  }
  if (hit < span.end) {
    record = vec4(maximum, sliceDepthAt(hit), sliceEyeDistanceAt(hit), 1.0);
  }
#endif
  if (inImage) imageStore(recordImage, pixel, record);
}
