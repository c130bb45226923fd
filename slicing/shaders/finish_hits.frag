// finish_hits.frag: once per frame, after the last slice, once per brick. Shades the first hit
// of every pixel, in the brick that owns the hit (each pixel is written once).
// In: the record (hit_records.glsl). The technique's own source, listed before this file,
// defines `uint finishState(vec4 record, float shade, inout float depth)`: the final state
// (e.g. a silhouette technique's leftover CONTOUR becomes SILHOUETTE, the right-angle test turns
// hits into lines). Out: (state, depth, shade, 0), shade = |n·v| at the first hit (0 for EMPTY).
layout(binding = UNIT_RECORD) uniform sampler2D recordTexture;
layout(location = 0) out vec4 result;

void main() {
  vec4 record = texelFetch(recordTexture, ivec2(gl_FragCoord.xy), 0);
  float depth = record.g;
  float shade = 0.0;
  if (uint(record.r) != STATE_EMPTY) {
    vec3 eye = eyePointAt(record.b);
    vec3 voxel = quantizedVoxel(voxelFromEyePoint(eye));
    // Drawn once per brick (hit_records.cpp finishRecords): the hit's brick shades it.
    if (!ownedByBrick(voxel)) discard;
    shade = facingRatio(voxel, eye);
  } else if (brickIsFirst == 0.0) {
    discard;
  }
  uint state = finishState(record, shade, depth);
  result = vec4(float(state), depth, shade, 0.0);
}
