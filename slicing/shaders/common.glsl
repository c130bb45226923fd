// common.glsl: put in front of every vsil shader (after #version and the defines).
// Pixel states, equal to vsil::PixelState (src/core/frame.h; a GL test checks they agree),
// and the geometry every slice pass shares: which volume sample a pixel sees on this slice.
// The CPU references in tests/reference repeat these formulas operation for operation.
#define STATE_EMPTY 0u
#define STATE_FILLED 1u
#define STATE_CONTOUR 2u
#define STATE_SILHOUETTE 3u

uniform sampler3D volumeTexture;      // data units, linear filtering, clamp to edge
uniform vec3 volumeDims;              // samples along x, y, z
uniform mat4 voxelFromEye;
uniform mat3 eyeFromVoxelGradient;    // inverse transpose of eyeFromVoxel's linear part
uniform vec2 viewportSize;
uniform vec2 halfExtent;              // View::halfExtent
uniform int orthographic;
uniform float isoValue;
uniform float sliceEyeDistance;       // -z_eye of this slice's plane
uniform float sliceDepth;             // its normalized depth d
uniform float sliceWindowDepth;       // its window depth (what the depth test compares)
// Where pixel centres sample the volume on this slice (slicer.h SliceTexCoords): texture
// coordinates affine in NDC, tex = ndc.x * sliceTexPerNdcX + ndc.y * sliceTexPerNdcY +
// sliceTexAtNdcOrigin. Cheaper per fragment than the eye point and the matrix.
uniform vec3 sliceTexPerNdcX;
uniform vec3 sliceTexPerNdcY;
uniform vec3 sliceTexAtNdcOrigin;

#ifdef VSIL_FRAGMENT_SHADER
// This pixel's centre in normalized device coordinates.
vec2 fragmentNdc() { return gl_FragCoord.xy / viewportSize * 2.0 - 1.0; }

// The eye-space point of this pixel's centre on the plane at eye distance `eyeDistance`.
vec3 eyePointAt(float eyeDistance) {
  vec2 ndc = fragmentNdc();
  float scale = orthographic != 0 ? 1.0 : eyeDistance;
  return vec3(ndc * halfExtent * scale, -eyeDistance);
}

// The texture coordinate this pixel's centre samples on this slice.
vec3 sliceTexCoord() {
  vec2 ndc = fragmentNdc();
  return ndc.x * sliceTexPerNdcX + ndc.y * sliceTexPerNdcY + sliceTexAtNdcOrigin;
}

#endif

vec3 voxelFromEyePoint(vec3 eye) { return (voxelFromEye * vec4(eye, 1.0)).xyz; }

// Inside the 3D texture's extent, texture coordinates 0 .. 1.
bool insideTexture(vec3 tex) {
  return all(greaterThanEqual(tex, vec3(0.0))) && all(lessThanEqual(tex, vec3(1.0)));
}

float sampleTexture(vec3 tex) { return texture(volumeTexture, tex).r; }

float sampleVolume(vec3 voxel) { return sampleTexture((voxel + 0.5) / volumeDims); }

// Central differences one voxel apart, in voxel-index units.
vec3 gradientVoxel(vec3 voxel) {
  return vec3(sampleVolume(voxel + vec3(1, 0, 0)) - sampleVolume(voxel - vec3(1, 0, 0)),
              sampleVolume(voxel + vec3(0, 1, 0)) - sampleVolume(voxel - vec3(0, 1, 0)),
              sampleVolume(voxel + vec3(0, 0, 1)) - sampleVolume(voxel - vec3(0, 0, 1))) * 0.5;
}

// |n·v|: 1 where the iso-surface faces the viewer, 0 where the view grazes it. A vanishing
// gradient has no direction; it counts as facing the viewer.
float facingRatio(vec3 voxel, vec3 eye) {
  vec3 normalEye = eyeFromVoxelGradient * gradientVoxel(voxel);
  float length2 = dot(normalEye, normalEye);
  if (length2 <= 0.0) return 1.0;
  vec3 toEye = orthographic != 0 ? vec3(0.0, 0.0, 1.0) : -normalize(eye);
  return abs(dot(normalEye * inversesqrt(length2), toEye));
}

// Nagy–Klein Table 2: the intermediate state t (rows) combined with this slice's contour value
// c (columns EMPTY, FILLED, CONTOUR, and SILHOUETTE, which c never is). The only copy in GLSL.
const uint decisionTable[16] = uint[16](
    STATE_EMPTY, STATE_FILLED, STATE_CONTOUR, STATE_EMPTY,                    // t = EMPTY
    STATE_FILLED, STATE_FILLED, STATE_FILLED, STATE_FILLED,                   // t = FILLED
    STATE_SILHOUETTE, STATE_FILLED, STATE_CONTOUR, STATE_CONTOUR,             // t = CONTOUR
    STATE_SILHOUETTE, STATE_SILHOUETTE, STATE_SILHOUETTE, STATE_SILHOUETTE);  // t = SILHOUETTE

uint decide(uint t, uint c) { return decisionTable[t * 4u + c]; }

// FILLED and SILHOUETTE never change again.
bool isFinal(uint state) { return state == STATE_FILLED || state == STATE_SILHOUETTE; }

// Footprints: the footprint pass writes footprintTag where this slice is FILLED; any other
// value is EMPTY. The fast pipeline tags each slice differently (its index + 1), so the
// footprint never needs clearing between slices; the paper pipeline clears and tags with 1.
uniform uint footprintTag;

// The contour value of a pixel from a footprint: STATE_CONTOUR for a FILLED pixel whose
// 8-neighbourhood is not all FILLED; pixels beyond the image count as EMPTY.
uint contourAt(usampler2D footprint, ivec2 pixel) {
  ivec2 size = textureSize(footprint, 0);
  if (texelFetch(footprint, pixel, 0).r != footprintTag) return STATE_EMPTY;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 neighbour = pixel + ivec2(dx, dy);
      if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size)) ||
          texelFetch(footprint, neighbour, 0).r != footprintTag) {
        return STATE_CONTOUR;
      }
    }
  }
  return STATE_FILLED;
}

// Records t = (state, depth, first-hit eye distance, depth of the latest CONTOUR sample).
// depth: for FILLED the first hit's normalized depth; for SILHOUETTE the middle of the run of
// CONTOUR samples that ended in the detection, where the view ray grazes the surface. The shade
// is computed once per pixel after the last slice (finish.frag): llvmpipe runs both sides of a
// branch, so per-slice gradients would cost every pixel.
float silhouetteDepth(vec4 t) { return 0.5 * (t.g + t.a); }

// Applies one slice's contour value c to the record t (the decision table, with the depths).
vec4 decideRecord(vec4 t, uint c) {
  uint state = uint(t.r);
  uint next = decide(state, c);
  vec4 result = vec4(float(next), t.g, t.b, t.a);
  if (state == STATE_EMPTY && next != STATE_EMPTY) {
    result.g = sliceDepth;
    result.b = sliceEyeDistance;
  }
  if (next == STATE_CONTOUR) result.a = sliceDepth;
  if (state == STATE_CONTOUR && next == STATE_SILHOUETTE) result.g = silhouetteDepth(t);
  return result;
}