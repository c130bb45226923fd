// mip_finish.frag (mip and demip, once per frame): the colour of each pixel from its maximum.
// In: the maximum (R32F, UNIT_AUXILIARY0); with DEMIP the first-hit record of the second sweep
// (UNIT_RECORD, hit_records.glsl: state, normalized depth d, eye distance, 1); with LMIP, at
// UNIT_AUXILIARY0, lmip's record instead (lmip_slice.frag) and the value it shows.
// Out: premultiplied RGBA. A pixel shows something (alpha 1) only where its maximum exceeds the
// window's low end; its grey is the window's ramp. With TRANSFER_TABLE (--tf) the value's colour
// and opacity from the table instead, where the opacity is above 0 (alpha = opacity). DEMIP
// (paper eq. 1 and 2), per channel of that colour:
//   c = colour * (1 - depthWeight) + 2 * depthWeight * (1 - depth), clamped to [0, 1],
//   colour = c * (1 - sphereWeight) + sphereColour * sphereWeight.
// With depthWeight = sphereWeight = 0 the result is exactly mip's (x*1 + 0 in float).
// COLOUR_SPHERE: sphereWeight > 0. Without it the sphere's term, c * 1 + sphereColour * 0, is c
// exactly (the sphere's colours are finite), and the pass skips the sphere's work (a third of
// the finish's time at 512²).
layout(binding = UNIT_AUXILIARY0) uniform sampler2D valueTexture;
#ifdef TRANSFER_TABLE
layout(binding = UNIT_TRANSFER_FUNCTION) uniform sampler1D transferTable;
uniform vec2 tableCoordFromValue;  // texture coordinate = value·x + y
// Below every value: where no slice sampled a pixel, its value is kNoSample (mip_technique.h).
const float kNothingSampled = -1.0e38;
#else
uniform vec2 window;  // low, high (data units)
#endif
layout(location = 0) out vec4 result;

#ifdef LMIP
uniform float lmipThreshold;
// The first local maximum at or above the threshold; the plain maximum where none is.
float shownValue(ivec2 pixel) {
  vec4 record = texelFetch(valueTexture, pixel, 0);
  return record.b >= lmipThreshold ? record.b : record.g;
}
#else
float shownValue(ivec2 pixel) { return texelFetch(valueTexture, pixel, 0).r; }
#endif

#ifdef DEMIP
layout(binding = UNIT_RECORD) uniform sampler2D recordTexture;
uniform float depthWeight;
#ifdef COLOUR_SPHERE
uniform float sphereWeight;
#ifdef SPHERE_MAP_IMAGE
// An equirectangular map (colour_sphere.h: u = 0.5 + λ/2π, v = 0.5 − φ/π, v = 0 the top row),
// GL_LINEAR, repeating in u, clamped in v.
layout(binding = UNIT_AUXILIARY1) uniform sampler2D sphereMap;
uniform mat3 sphereFromEye;  // eye-space directions into the sphere's frame (right, up, front)
#else
uniform vec3 sphereFrontEye;  // where the map's front colour points (colour_sphere.h)
uniform vec3 sphereFrontColour;
uniform vec3 sphereBackColour;
#endif
uniform vec3 volumeCentreEye;
#endif
uniform vec2 depthRangeEye;  // eye distances of normalized depth 0 and 1

// Where this pixel's ray enters the volume's box, in normalized depth (0 if in front of it):
// the ray from depth 0 to depth 1 is linear in d for both projections (eyePointAt).
float boxEntryDepth(out vec3 entryVoxel) {
  vec3 a = voxelFromEyePoint(eyePointAt(depthRangeEye.x));
  vec3 b = voxelFromEyePoint(eyePointAt(depthRangeEye.y));
  vec3 direction = b - a;
  float entry = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (direction[axis] == 0.0) continue;  // parallel to the slab: inside it (or never hit)
    float t0 = (-0.5 - a[axis]) / direction[axis];
    float t1 = (volumeDims[axis] - 0.5 - a[axis]) / direction[axis];
    entry = max(entry, min(t0, t1));
  }
  entryVoxel = a + entry * direction;
  return entry;
}

// The depth the weighting uses (--depth-mode): DEPTH_STEPS the ray's length inside the box
// before the hit; DEPTH_ENTRY_PLUS_STEPS that plus the entry's OpenGL window depth; else exact.
float weightingDepth(float hitDepth) {
#if defined(DEPTH_STEPS) || defined(DEPTH_ENTRY_PLUS_STEPS)
  vec3 entryVoxel;
  float steps = hitDepth - boxEntryDepth(entryVoxel);
#ifdef DEPTH_STEPS
  return steps;
#else
  vec4 clip = clipFromVoxel * vec4(entryVoxel, 1.0);
  return clip.z / clip.w * 0.5 + 0.5 + steps;
#endif
#else
  return hitDepth;
#endif
}

#ifdef COLOUR_SPHERE
// The colour sphere toward the hit from the volume's centre (colour_sphere.h).
vec3 sphereColour(float hitEyeDistance) {
  vec3 fromCentre = eyePointAt(hitEyeDistance) - volumeCentreEye;
  float length2 = dot(fromCentre, fromCentre);
#ifdef SPHERE_MAP_IMAGE
  // The centre itself has no direction: it takes the image's centre.
  vec2 uv = vec2(0.5);
  if (length2 > 0.0) {
    const float kPi = 3.14159265358979;
    vec3 d = sphereFromEye * fromCentre;
    // Straight up or down the longitude is arbitrary: GLSL leaves atan(0, 0) undefined,
    // std::atan2 gives 0, and both take 0.
    float longitude = d.x != 0.0 || d.z != 0.0 ? atan(d.x, d.z) : 0.0;
    float latitude = atan(d.y, length(d.xz));
    uv = vec2(0.5 + longitude / (2.0 * kPi), 0.5 - latitude / kPi);
  }
  return texture(sphereMap, uv).rgb;
#else
  // The centre itself has no direction: it takes the sphere's middle.
  float facing = length2 > 0.0 ? dot(fromCentre * inversesqrt(length2), sphereFrontEye) : 0.0;
  return mix(sphereBackColour, sphereFrontColour, 0.5 + 0.5 * facing);
#endif
}
#endif
#endif

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float maximum = shownValue(pixel);
#ifdef TRANSFER_TABLE
  vec4 classified = maximum > kNothingSampled
                        ? texture(transferTable, maximum * tableCoordFromValue.x + tableCoordFromValue.y)
                        : vec4(0.0);
  if (!(classified.a > 0.0)) {
    result = vec4(0.0);
    return;
  }
  vec3 colour = classified.rgb;
  float opacity = classified.a;
#else
  if (!(maximum > window.x)) {
    result = vec4(0.0);
    return;
  }
  vec3 colour = vec3(clamp((maximum - window.x) / (window.y - window.x), 0.0, 1.0));
  float opacity = 1.0;
#endif
#ifdef DEMIP
  vec4 record = texelFetch(recordTexture, pixel, 0);
  vec3 c = clamp(colour * (1.0 - depthWeight) + 2.0 * depthWeight * (1.0 - weightingDepth(record.g)),
                 0.0, 1.0);
#ifdef COLOUR_SPHERE
  colour = c * (1.0 - sphereWeight) + sphereColour(record.b) * sphereWeight;
#else
  colour = c;
#endif
#endif
  result = vec4(colour * opacity, opacity);
}
