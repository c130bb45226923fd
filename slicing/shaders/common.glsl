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

#ifdef VSIL_FRAGMENT_SHADER
// The eye-space point of this pixel's centre on the slice plane.
vec3 slicePointEye() {
  vec2 ndc = gl_FragCoord.xy / viewportSize * 2.0 - 1.0;
  float scale = orthographic != 0 ? 1.0 : sliceEyeDistance;
  return vec3(ndc * halfExtent * scale, -sliceEyeDistance);
}

#endif

vec3 voxelFromEyePoint(vec3 eye) { return (voxelFromEye * vec4(eye, 1.0)).xyz; }

// Inside the 3D texture's extent, voxel coordinates -0.5 .. dim - 0.5.
bool insideVolume(vec3 voxel) {
  return all(greaterThanEqual(voxel, vec3(-0.5))) && all(lessThanEqual(voxel, volumeDims - 0.5));
}

float sampleVolume(vec3 voxel) { return texture(volumeTexture, (voxel + 0.5) / volumeDims).r; }

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
