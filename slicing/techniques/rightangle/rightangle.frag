// rightangle.frag: the right-angle baseline (RA), one pass per slice, front to back. A sample
// at or above the iso value is a hit; blending (ONE_MINUS_DST_ALPHA, DST_ALPHA) keeps the first
// one, since a pixel's alpha turns 1 with its first hit. The depth test (GREATER, no writes)
// skips pixels in front of the first occupied brick and, once marked (mark_dead.frag), pixels
// that have their hit, before any sampling. (A shader that discards and writes stencil loses
// llvmpipe's early test, so the first hit is not kept by a stencil.)
// Out: the record (STATE_FILLED, depth, first-hit eye distance, 1); finishState below then
// applies the line test once per pixel (finish_hits.frag).
layout(location = 0) out vec4 result;

void main() {
  vec3 tex = sliceTexCoord();
  if (!insideTexture(tex) || sampleTexture(tex) < isoValue) discard;
  result = vec4(float(STATE_FILLED), sliceDepth, sliceEyeDistance, 1.0);
}
