// mark_dead.frag (fast silhouette pipeline, every few slices): keeps only "dead" pixels, whose
// own record and those of all 8 neighbours are final (FILLED or SILHOUETTE); the caller writes
// depth 1 there. Nothing a later slice does can change such a pixel or a neighbour's decision,
// so the footprint pass (depth test GREATER) skips it before its shader runs.
// In: intermediateTexture (the record, common.glsl). Out: depth only.
uniform sampler2D intermediateTexture;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(intermediateTexture, 0);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), size - 1);
      if (!isFinal(uint(texelFetch(intermediateTexture, q, 0).r))) discard;
    }
  }
}
