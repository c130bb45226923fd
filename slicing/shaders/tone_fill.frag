// tone_fill.frag: `--fill tone` (slicing/tone_fill.h), once per frame after the last slice, for
// the techniques that return pixel states. Colours the first iso-surface hit of every pixel with
// the formulas of illustration.glsl, in eye space: the lit colour I_G of the fill colour, tone
// shading, then distance colour blending by the hit's normalized depth.
// In: the record before the finishing pass (hit_records.glsl: state, normalized depth d,
// first-hit eye distance), reading pixels whose state is not EMPTY. The normal is the one
// finish_hits.frag takes |n·v| from: central differences at the (quantized) voxel position of
// the hit. Drawn once per brick (technique.h drawScreenPerBrick), as finish_hits.frag is: the
// brick that owns the hit shades it, from its own texture (the others do not hold the hit's
// neighbourhood), so bricks give the bytes of one texture.
// Out: (r, g, b, 1) straight, not clamped, at hits; 0 elsewhere. The caller keeps the FILLED
// pixels of the finished states.
layout(binding = UNIT_RECORD) uniform sampler2D recordTexture;
uniform vec3 fillColor;  // c_o
layout(location = 0) out vec4 result;

void main() {
  vec4 record = texelFetch(recordTexture, ivec2(gl_FragCoord.xy), 0);
  if (uint(record.r) == STATE_EMPTY) {
    if (brickIsFirst == 0.0) discard;
    result = vec4(0.0);
    return;
  }
  vec3 eye = eyePointAt(record.b);
  vec3 voxel = quantizedVoxel(voxelFromEyePoint(eye));
  if (!ownedByBrick(voxel)) discard;
  vec3 n = outwardNormalEye(voxel);
  vec3 color = toneShade(litColor(fillColor, n), fillColor, n);
  result = vec4(distanceBlend(color, record.g), 1.0);
}
