// contour.frag (silhouette pass 2 of 3): contour of the footprint.
// In: footprintTexture (0 EMPTY, 1 FILLED). Out: STATE_EMPTY, STATE_FILLED, or STATE_CONTOUR
// for a FILLED pixel whose 8-neighbourhood is not all FILLED (pixels beyond the image count
// as EMPTY).
uniform usampler2D footprintTexture;
layout(location = 0) out uint contour;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(footprintTexture, 0);
  if (texelFetch(footprintTexture, pixel, 0).r == 0u) {
    contour = STATE_EMPTY;
    return;
  }
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 neighbour = pixel + ivec2(dx, dy);
      if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size)) ||
          texelFetch(footprintTexture, neighbour, 0).r == 0u) {
        contour = STATE_CONTOUR;
        return;
      }
    }
  }
  contour = STATE_FILLED;
}
