// mark_dead.frag (every few slices): keeps only "dead" pixels, which no later slice can change;
// the caller writes depth 1 there, so slice passes testing GREATER skip them before their
// shader runs. In the silhouette pipeline a pixel is dead when its own record and those of all
// 8 neighbours are final (FILLED or SILHOUETTE): nothing a later slice does can change it or a
// neighbour's decision. With OWN_RECORD_ONLY (rightangle) a pixel is dead once it has its hit.
// Either way a pixel is dead once the slices are past the last occupied brick on its ray
// (slicing/empty_space.h): every later sample there stays below the iso value, which is what
// a skipped pixel's cleared footprint says.
// In: intermediateTexture (the record, common.glsl), exitDepthTexture (window depth where the
// ray leaves occupied space for good). Out: depth only.
uniform sampler2D intermediateTexture;
uniform sampler2D exitDepthTexture;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (sliceWindowDepth >= texelFetch(exitDepthTexture, pixel, 0).r) return;
#ifdef OWN_RECORD_ONLY
  if (!isFinal(uint(texelFetch(intermediateTexture, pixel, 0).r))) discard;
#else
  ivec2 size = textureSize(intermediateTexture, 0);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), size - 1);
      if (!isFinal(uint(texelFetch(intermediateTexture, q, 0).r))) discard;
    }
  }
#endif
}
