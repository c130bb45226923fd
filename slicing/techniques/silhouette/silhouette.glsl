// silhouette.glsl: Nagy–Klein's decision table and what the silhouette passes share. After
// shaders/common.glsl and shaders/hit_records.glsl in every silhouette program.
// The record t (hit_records.glsl) here: (state, depth, first-hit eye distance, depth of the
// latest CONTOUR sample). depth: for FILLED the first hit's normalized depth; for SILHOUETTE the
// middle of the run of CONTOUR samples that ended in the detection, where the view ray grazes
// the surface.

// Nagy–Klein Table 2: the record's state t (rows) combined with this slice's contour value c
// (columns EMPTY, FILLED, CONTOUR, and SILHOUETTE, which c never is). The only copy in GLSL.
const uint decisionTable[16] = uint[16](
    STATE_EMPTY, STATE_FILLED, STATE_CONTOUR, STATE_EMPTY,                    // t = EMPTY
    STATE_FILLED, STATE_FILLED, STATE_FILLED, STATE_FILLED,                   // t = FILLED
    STATE_SILHOUETTE, STATE_FILLED, STATE_CONTOUR, STATE_CONTOUR,             // t = CONTOUR
    STATE_SILHOUETTE, STATE_SILHOUETTE, STATE_SILHOUETTE, STATE_SILHOUETTE);  // t = SILHOUETTE

uint decide(uint t, uint c) { return decisionTable[t * 4u + c]; }

// The table applied to many pixels at once (the tile march, march.comp): bit j of states[t] is
// set where pixel j's record is t, of contours[c] where its contour value is c (EMPTY, FILLED,
// CONTOUR). With t and c constants, decide(t, c) folds away: a few bit operations in all.
void decideBits(inout uint states[4], uint contours[3]) {
  uint next[4] = uint[4](0u, 0u, 0u, 0u);
  for (uint t = 0u; t < 4u; ++t) {
    for (uint c = 0u; c < 3u; ++c) next[decide(t, c)] |= states[t] & contours[c];
  }
  states = next;
}

#ifndef VSIL_COMPUTE_SHADER
// Footprints: the footprint pass writes footprintTag() where this slice is FILLED; any other
// value is EMPTY. The fast pipeline tags each slice differently (its index + 1), so the
// footprint never needs clearing between slices; the paper pipeline (PAPER_PIPELINE) clears
// and tags with 1.
uint footprintTag() {
#ifdef PAPER_PIPELINE
  return 1u;
#else
  return sliceIndex + 1u;
#endif
}

// The contour value of a pixel from a footprint: STATE_CONTOUR for a FILLED pixel whose
// 8-neighbourhood is not all FILLED. Pixels beyond the image are not known, so they are no
// neighbours: counting them EMPTY drew a false line along every border the surface crosses
// when the view clips the object. Their coordinates are clamped to the image, which makes
// such a neighbour the pixel itself or one of its other neighbours.
uint contourAt(usampler2D footprint, ivec2 pixel) {
  uint tag = footprintTag();
  ivec2 last = textureSize(footprint, 0) - 1;
  if (texelFetch(footprint, pixel, 0).r != tag) return STATE_EMPTY;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 neighbour = clamp(pixel + ivec2(dx, dy), ivec2(0), last);
      if (texelFetch(footprint, neighbour, 0).r != tag) return STATE_CONTOUR;
    }
  }
  return STATE_FILLED;
}

#endif

float silhouetteDepth(vec4 t) { return 0.5 * (t.g + t.a); }

// Applies the contour value c of a slice at normalized depth `depth` and eye distance
// `eyeDistance` to the record t (the decision table, with the depths).
vec4 decideRecordAt(vec4 t, uint c, float depth, float eyeDistance) {
  uint state = uint(t.r);
  uint next = decide(state, c);
  vec4 result = vec4(float(next), t.g, t.b, t.a);
  if (state == STATE_EMPTY && next != STATE_EMPTY) {
    result.g = depth;
    result.b = eyeDistance;
  }
  if (next == STATE_CONTOUR) result.a = depth;
  if (state == STATE_CONTOUR && next == STATE_SILHOUETTE) result.g = silhouetteDepth(t);
  return result;
}

#ifndef VSIL_COMPUTE_SHADER
// The same for the slice this pass draws.
vec4 decideRecord(vec4 t, uint c) { return decideRecordAt(t, c, sliceDepth, sliceEyeDistance); }
#endif

// For finish_hits.frag: a CONTOUR record left after the last slice met the extra empty slice
// behind the volume and becomes SILHOUETTE (the fast pipeline applies detection lazily,
// decision_inplace.frag).
uint finishState(vec4 record, float shade, inout float depth) {
  uint state = uint(record.r);
  if (state != STATE_CONTOUR) return state;
  depth = silhouetteDepth(record);
  return STATE_SILHOUETTE;
}
