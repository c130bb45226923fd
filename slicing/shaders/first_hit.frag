// first_hit.frag: the first sample at or above the iso value along each ray, one pass per slice,
// front to back (slicing/hit_records.h FirstHitRecorder; rightangle, firsthit, demip). Blending
// (ONE_MINUS_DST_ALPHA, DST_ALPHA) keeps the first hit, since a pixel's alpha turns 1 with it.
// The depth test (GREATER, no writes) skips pixels in front of the first occupied brick and,
// once marked (mark_dead.frag), pixels that have their hit, before any sampling. (A shader that
// discards and writes stencil loses llvmpipe's early test, so the first hit is not kept by a
// stencil.)
// Out: the record (STATE_FILLED, depth, first-hit eye distance, 1) (hit_records.glsl).
// With MATERIAL_THRESHOLD (demip's second sweep) the threshold is per pixel: the pixel's maximum
// over the first sweep (R32F, UNIT_AUXILIARY0) less materialEps, the first sample of the same
// material as the maximum.
layout(location = 0) out vec4 result;

#ifdef MATERIAL_THRESHOLD
layout(binding = UNIT_AUXILIARY0) uniform sampler2D maximumTexture;
uniform float materialEps;
float hitThreshold() { return texelFetch(maximumTexture, ivec2(gl_FragCoord.xy), 0).r - materialEps; }
#else
float hitThreshold() { return isoValue; }
#endif

void main() {
  vec3 voxel = sliceVoxel();
  if (!insideVolume(voxel) || sampleVolume(voxel) < hitThreshold()) discard;
  result = vec4(float(STATE_FILLED), sliceDepth, sliceEyeDistance, 1.0);
}
