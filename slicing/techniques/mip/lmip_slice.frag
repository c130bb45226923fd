// lmip_slice.frag (lmip, per slice): the search for the first local maximum at or above
// lmipThreshold along each ray, the record updated in place (as silhouette's
// decision_inplace.frag: read through recordTexture, written through recordImage, a
// texture-fetch barrier between slices).
// Record (RGBA32F): r found (STATE_FILLED once the maximum is found, so mark_dead.frag retires
// the pixel; 0 before), g the plain maximum so far, b the candidate (the highest sample of the
// current run at or above the threshold; kNoSample before one), a the candidate's depth d.
// A run ends when a sample falls below the candidate: the candidate is the first local maximum.
layout(early_fragment_tests) in;  // the depth test must skip before the store, not after
layout(binding = UNIT_RECORD) uniform sampler2D recordTexture;
layout(binding = IMAGE_RECORD, rgba32f) uniform writeonly restrict image2D recordImage;
uniform float lmipThreshold;

void main() {
  vec3 voxel = sliceVoxel();
  if (!insideVolume(voxel)) return;
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 t = texelFetch(recordTexture, pixel, 0);
  if (isFinal(uint(t.r))) return;
  float value = sampleVolume(voxel);
  t.g = max(t.g, value);
  if (t.b >= lmipThreshold && value < t.b) {
    t.r = float(STATE_FILLED);
  } else if (value >= lmipThreshold && value > t.b) {
    t.b = value;
    t.a = sliceDepth;
  }
  imageStore(recordImage, pixel, t);
}
