// lmip_march.comp (lmip when the volume is one texture; lmip_technique.h): lmip_slice.frag's
// search as a march (shaders/tile_march.glsl), one invocation per pixel of a tile, no apron.
// Each invocation starts at the first slice beyond where its ray enters the volume's bricks
// and walks its slices front to back, sampling where lmip_slice.frag samples, until its run
// above the threshold falls (the first local maximum) or its ray leaves the volume. The record
// is lmip_slice.frag's (r found, g the plain maximum so far, b the candidate, a its depth), so
// a dispatch continues where the one before left it and mip_finish.frag reads it unchanged.
layout(local_size_x = MARCH_TILE_X, local_size_y = MARCH_TILE_Y) in;

uniform float lmipThreshold;
uniform float noSample;

void main() {
  ivec2 pixel = tileOrigin() + ivec2(gl_LocalInvocationID.xy);
  bool inImage = insideImage(pixel);
  vec4 t = vec4(0.0, noSample, noSample, 0.0);
  if (continuesMarch() && inImage) t = imageLoad(recordImage, pixel);
  float entryDepth = inImage ? entryDepthAt(pixel) : 1.0;
  float exitDepth = inImage && !isFinal(uint(t.r)) ? exitDepthAt(pixel) : 0.0;
  SliceSpan span = sliceSpan(tileFirstSlice(entryDepth), entryDepth, exitDepth);
  PixelRay ray = pixelRay(pixelCentre(pixel));
  int candidate = -1;  // the slice of a new candidate in this dispatch (its depth read once)
  for (int k = span.first; k < span.end; ++k) {
    vec3 voxel = rayVoxel(ray, k);
    if (!insideVolume(voxel)) continue;
    float value = sampleVolume(voxel);
    t.g = max(t.g, value);
    if (t.b >= lmipThreshold && value < t.b) {
      t.r = float(STATE_FILLED);
      break;
    }
    if (value >= lmipThreshold && value > t.b) {
      t.b = value;
      candidate = k;
    }
  }
  if (candidate >= 0) t.a = sliceDepthAt(candidate);
  if (inImage) imageStore(recordImage, pixel, t);
}
