// common.glsl: first in every vsil program (shader_program.h). What every technique shares: the
// frame's and the slice's uniform blocks (slicing/frame_uniforms.h mirrors them), which volume
// sample a pixel sees on this slice, and gradients by central differences. The CPU references
// in tests/reference repeat these formulas operation for operation.

layout(std140, binding = 0) uniform FrameBlock {
  mat4 voxelFromEye;
  mat4 clipFromVoxel;
  mat3 eyeFromVoxelGradient;  // inverse transpose of eyeFromVoxel's linear part
  vec3 volumeDims;            // samples along x, y, z
  int orthographic;
  vec2 viewportSize;
  vec2 halfExtent;  // View::halfExtent
};

#ifndef VSIL_COMPUTE_SHADER
// The slice a pass draws (compute shaders read slices by index: tile_march.glsl sliceAt).
layout(std140, binding = 1) uniform SliceBlock {
  // Where pixel centres sample the volume on this slice (slicer.h SliceTexCoords): texture
  // coordinates affine in NDC, tex = ndc.x * sliceTexPerNdcX + ndc.y * sliceTexPerNdcY +
  // sliceTexAtNdcOrigin. Cheaper per fragment than the eye point and the matrix.
  vec3 sliceTexPerNdcX;
  float sliceEyeDistance;  // -z_eye of this slice's plane
  vec3 sliceTexPerNdcY;
  float sliceDepth;  // its normalized depth d
  vec3 sliceTexAtNdcOrigin;
  float sliceWindowDepth;    // its window depth (what the depth test compares)
  float previousSliceDepth;  // the previous slice's d (0 before the first)
  uint sliceIndex;
};
#endif

layout(binding = UNIT_VOLUME) uniform sampler3D volumeTexture;  // data units, linear, clamped

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

#ifdef VSIL_COMPUTE_SHADER
// Pixel `pixel`'s centre in NDC, the same operations as fragmentNdc() on gl_FragCoord (the
// pixel + 0.5), so that a compute shader samples exactly where a slice pass does.
vec2 pixelNdc(ivec2 pixel) { return (vec2(pixel) + 0.5) / viewportSize * 2.0 - 1.0; }

// The texture coordinate a pixel centre at `ndc` samples on a slice whose SliceBlock holds
// these coefficients (sliceTexCoord()'s operations).
vec3 sliceTexCoordAt(vec3 texPerNdcX, vec3 texPerNdcY, vec3 texAtNdcOrigin, vec2 ndc) {
  return ndc.x * texPerNdcX + ndc.y * texPerNdcY + texAtNdcOrigin;
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

// The iso-surface's outward unit normal n = −∇f/|∇f| in eye space (out of the denser side, as
// shaders/illustration.glsl takes it); 0 where the gradient vanishes.
vec3 outwardNormalEye(vec3 voxel) {
  vec3 gradientEye = eyeFromVoxelGradient * gradientVoxel(voxel);
  float length2 = dot(gradientEye, gradientEye);
  return length2 > 0.0 ? gradientEye * -inversesqrt(length2) : vec3(0.0);
}

// |n·v|: 1 where the iso-surface faces the viewer, 0 where the view grazes it. A vanishing
// gradient has no direction; it counts as facing the viewer.
float facingRatio(vec3 voxel, vec3 eye) {
  vec3 n = outwardNormalEye(voxel);
  if (n == vec3(0.0)) return 1.0;
  vec3 toEye = orthographic != 0 ? vec3(0.0, 0.0, 1.0) : -normalize(eye);
  return abs(dot(n, toEye));
}
