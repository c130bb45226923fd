// contour.frag (paper pipeline, pass 2 of 3): contour of the footprint.
// In: the footprint (footprintTag() FILLED, anything else EMPTY; silhouette.glsl).
// Out: STATE_EMPTY, STATE_FILLED or STATE_CONTOUR (contourAt in silhouette.glsl).
layout(binding = UNIT_FOOTPRINT) uniform usampler2D footprintTexture;
layout(location = 0) out uint contour;

void main() { contour = contourAt(footprintTexture, ivec2(gl_FragCoord.xy)); }
