// max_march.comp (mip and demip when the volume is one texture; mip_technique.h): each pixel's
// maximum over the slices and, with DEMIP, the first sample of its material, in one compute
// dispatch (shaders/tile_march.glsl): one invocation per pixel of a MARCH_TILE_X x MARCH_TILE_Y
// tile, sampling exactly where max_sample.frag and first_hit.frag do, on the slices beyond
// where its ray enters occupied bricks (the slice passes' GREATER test) up to where it leaves
// them for good (tile_march.glsl sliceSpan; past there every sample lies in bricks that cannot
// hold a shown maximum: mip_technique.cpp occupancy).
// DEMIP: a second loop finds the first sample within materialEps of the maximum, from a bound
// the first loop keeps on where it can be. Every sample before a new running maximum is at most
// the old one, so when a new maximum v arrives: if the old maximum is below v − eps, no sample
// before v can be the hit (the final threshold is at least v − eps); else if the candidate (the
// last maximum that rose more than eps above the candidate before it) is below v − eps, neither
// it nor any sample before it can. The second loop then covers about the last rise of eps
// before the hit instead of the whole ray up to it.
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
  int hitLowerBound = span.first;  // no slice before it holds the hit
  int candidateSlice = span.first;
  float candidateValue = noSample;
#endif
  for (int k = span.first; k < span.end; ++k) {
    vec3 voxel = rayVoxel(ray, k);
    if (insideVolume(voxel)) {
      float value = sampleVolume(voxel);
#ifdef DEMIP
      if (value > maximum) {
        bool passesCandidate = value - materialEps > candidateValue;
        if (value - materialEps > maximum) {
          hitLowerBound = k;
        } else if (passesCandidate) {
          hitLowerBound = max(hitLowerBound, candidateSlice + 1);
        }
        if (passesCandidate) {
          candidateSlice = k;
          candidateValue = value;
        }
      }
#endif
      maximum = max(maximum, value);
    }
  }
  vec4 record = vec4(maximum, 0.0, 0.0, 0.0);
#ifdef DEMIP
  float threshold = maximum - materialEps;
  int hit = span.end;
  for (int k = hitLowerBound; k < span.end; ++k) {
    vec3 voxel = rayVoxel(ray, k);
    if (insideVolume(voxel) && sampleVolume(voxel) >= threshold) {
      hit = k;
      break;
    }
  }
  if (hit < span.end) {
    SliceParams slice = sliceAt(hit);
    record = vec4(maximum, slice.depth, slice.eyeDistance, 1.0);
  }
#endif
  if (inImage) imageStore(recordImage, pixel, record);
}
