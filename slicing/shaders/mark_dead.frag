// mark_dead.frag (every few slices): keeps only "dead" pixels, which no later slice can change;
// the caller writes depth 1 there, so slice passes testing GREATER then skip them before their
// shader runs. Without NEIGHBOURS_FINAL (rightangle, firsthit) a pixel is dead once its own
// record is final; with it (silhouette) when its own record and those of all 8 neighbours are
// final (FILLED or SILHOUETTE): nothing a later slice does can change it or a neighbour's
// decision. With OPACITY_DEAD (compositing techniques, slicing/compositing.h) when the opacity
// it has accumulated (the record's alpha) reached deadOpacity: early ray termination. Either
// way a pixel is dead once the slices are past the last occupied brick on its ray
// (slicing/empty_space.h): every later sample there is one the technique skips anyway.
// SLAB_OWNED_MARKS (a slab of a relayed frame): see main.
// In: the record (hit_records.glsl), the exit depth (window depth where the ray leaves occupied
// space for good). Out: depth only.
layout(binding = UNIT_RECORD) uniform sampler2D recordTexture;
layout(binding = UNIT_EXIT_DEPTH) uniform sampler2D exitDepthTexture;

#if defined(OPACITY_DEAD)
uniform float deadOpacity;
#endif

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#if defined(SLAB_OWNED_MARKS)
  // A relayed slab (slicing/slab.h): only where this slice's sample lies in the slab (this
  // piece's brick owns it, as in the slice pass). Before it, the accumulated opacity is the
  // slab in front's whole ray, not the samples up to this slice; after it, the slab has no
  // sample left to skip, and the slab behind decides with the samples up to this slice.
  if (!ownedByBrick(sliceVoxel())) discard;
#endif
  if (sliceWindowDepth >= texelFetch(exitDepthTexture, pixel, 0).r) return;
#if defined(OPACITY_DEAD)
  if (texelFetch(recordTexture, pixel, 0).a < deadOpacity) discard;
#elif defined(NEIGHBOURS_FINAL)
  ivec2 size = textureSize(recordTexture, 0);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), size - 1);
      if (!isFinal(uint(texelFetch(recordTexture, q, 0).r))) discard;
    }
  }
#else
  if (!isFinal(uint(texelFetch(recordTexture, pixel, 0).r))) discard;
#endif
}
