// firsthit.frag: the first sample at or above the iso value along each ray, front to back.
// Blending (ONE_MINUS_DST_ALPHA, DST_ALPHA) keeps the first one, since a pixel's alpha turns 1
// with its first hit; the depth test (GREATER, no writes) skips empty space in front and pixels
// marked dead once they have their hit (shaders/mark_dead.frag).
// Out: the record (STATE_FILLED, depth, first-hit eye distance, 1) (shaders/hit_records.glsl).
layout(location = 0) out vec4 result;

void main() {
  vec3 tex = sliceTexCoord();
  if (!insideTexture(tex) || sampleTexture(tex) < isoValue) discard;
  result = vec4(float(STATE_FILLED), sliceDepth, sliceEyeDistance, 1.0);
}
