// common.glsl: first in every vsil program (shader_program.h). What every technique shares: the
// frame's, the slice's and the brick's uniform blocks (slicing/frame_uniforms.h mirrors them),
// which volume sample a pixel sees on this slice, and gradients by central differences. The CPU
// references in tests/reference repeat these formulas operation for operation.

layout(std140, binding = 0) uniform FrameBlock {
  mat4 voxelFromEye;
  mat4 clipFromVoxel;
  mat3 eyeFromVoxelGradient;  // inverse transpose of eyeFromVoxel's linear part
  vec3 volumeDims;            // samples along x, y, z
  int orthographic;
  vec2 viewportSize;
  vec2 halfExtent;  // View::halfExtent
  // The MIP family's sampling (slicer.h PixelRays, RAY_SAMPLING below): a pixel's ray in voxel
  // coordinates from the first slice's plane, affine in window coordinates; slice k's sample
  // lies float(k) * rayStepEye along it.
  vec3 rayOriginPerWindowX;
  float rayStepEye;
  vec3 rayOriginPerWindowY;
  vec3 rayOriginAtWindowOrigin;
  vec3 rayDirectionPerWindowX;
  vec3 rayDirectionPerWindowY;
  vec3 rayDirectionAtWindowOrigin;
};

#ifndef VSIL_COMPUTE_SHADER
// The slice a pass draws (compute shaders read slices by index: tile_march.glsl sliceAt).
layout(std140, binding = 1) uniform SliceBlock {
  // Where pixel centres sample the volume on this slice (slicer.h SliceVoxelCoords): voxel
  // coordinates affine in NDC, voxel = ndc.x * sliceVoxelPerNdcX + ndc.y * sliceVoxelPerNdcY +
  // sliceVoxelAtNdcOrigin. Cheaper per fragment than the eye point and the matrix.
  vec3 sliceVoxelPerNdcX;
  float sliceEyeDistance;  // -z_eye of this slice's plane
  vec3 sliceVoxelPerNdcY;
  float sliceDepth;  // its normalized depth d
  vec3 sliceVoxelAtNdcOrigin;
  float sliceWindowDepth;    // its window depth (what the depth test compares)
  float previousSliceDepth;  // the previous slice's d (0 before the first)
  uint sliceIndex;
};
#endif

// The brick this piece of a slice samples (core/brick_layout.h, slicing/volume_texture.h): its
// textures (the volume's, and the gradients' where a technique reads them) hold the voxels
// from brickOrigin on, and are powers of two in size.
layout(std140, binding = 3) uniform BrickBlock {
  vec3 brickOrigin;       // the voxel in texel 0 (integers)
  vec3 brickTexPerVoxel;  // 1 / the textures' size (powers of two)
  vec3 brickLow;          // the sample positions it owns: brickLow <= p < brickHigh
  float brickIsFirst;     // 1 for the first brick (screen passes per brick: who writes misses)
  vec3 brickHigh;
};

layout(binding = UNIT_VOLUME) uniform sampler3D volumeTexture;  // data units, linear, clamped

// Sample positions are rounded to 1/1024 voxel (BrickLayout::kSampleQuantum): then every step of
// brickTexCoord and of the sampler's texel-space u·size − 0.5 is exact in float, so a sample
// filters the same voxels with the same weights in whichever brick it lies (one brick or many
// give the same bytes).
vec3 quantizedVoxel(vec3 voxel) { return floor(voxel * 1024.0 + 0.5) * (1.0 / 1024.0); }

// Whether this piece's brick owns a (quantized) voxel position: every position has one owner.
bool ownedByBrick(vec3 voxel) {
  return all(greaterThanEqual(voxel, brickLow)) && all(lessThan(voxel, brickHigh));
}

// A pixel's ray (slicer.h PixelRays): where the MIP family's samples lie. Their slice passes
// and marches compute them with these same operations, so both sample the same positions.
struct PixelRay {
  vec3 origin;     // on the first slice's plane
  vec3 direction;  // voxels per unit of eye distance
};

// The ray through the pixel centre at window coordinates `w` (gl_FragCoord.xy).
PixelRay pixelRay(vec2 w) {
  return PixelRay(w.x * rayOriginPerWindowX + w.y * rayOriginPerWindowY + rayOriginAtWindowOrigin,
                  w.x * rayDirectionPerWindowX + w.y * rayDirectionPerWindowY +
                      rayDirectionAtWindowOrigin);
}

// The (quantized) voxel position where a ray crosses slice k of the plan.
vec3 rayVoxel(PixelRay ray, int k) {
  return quantizedVoxel(ray.origin + (float(k) * rayStepEye) * ray.direction);
}

// BOX_ALIGNED_SAMPLING (the compositing techniques, slicing/compositing.h): a pixel's samples lie
// on its ray (pixelRay) at whole steps from half a step past where the ray enters the volume's
// box, not on the slice planes: slice k samples (k − boxPhase)·rayStepEye along it, boxPhase in
// [0, 1) the same for every slice. On the planes, the first sample past a face of the box lies
// anywhere from 0 to a step inside, varying along the face with the planes' phase; where the
// box itself is the visible surface (a volume opaque up to its faces, gen:cube) the samples
// then cross the region of the next face's normals in a periodic pattern, a rope along the
// edges and a stair along the outline that only more slices shrink.
float boxPhase(PixelRay ray) {
  // Three reciprocals instead of six divisions; an axis the ray runs along exactly (1/0 = inf)
  // gets ±1e30, finite, so that 0·it stays 0 (as in the CPU reference).
  vec3 inverse = clamp(1.0 / ray.direction, vec3(-1e30), vec3(1e30));
  vec3 toLow = (vec3(-0.5) - ray.origin) * inverse;
  vec3 toHigh = (volumeDims - 0.5 - ray.origin) * inverse;
  vec3 enter = min(toLow, toHigh);
  float entry = max(max(enter.x, enter.y), enter.z);
  return fract(-entry / rayStepEye - 0.5);
}

// Slice k's sample on a ray under BOX_ALIGNED_SAMPLING (quantized); `phase` is boxPhase(ray).
vec3 boxAlignedVoxel(PixelRay ray, float phase, int k) {
  return quantizedVoxel(ray.origin + ((float(k) - phase) * rayStepEye) * ray.direction);
}

// The eye-space point of the pixel centre at `ndc` on the plane at eye distance `eyeDistance`.
vec3 eyePointAtNdc(vec2 ndc, float eyeDistance) {
  float scale = orthographic != 0 ? 1.0 : eyeDistance;
  return vec3(ndc * halfExtent * scale, -eyeDistance);
}

#ifdef VSIL_FRAGMENT_SHADER
// This pixel's centre in normalized device coordinates.
vec2 fragmentNdc() { return gl_FragCoord.xy / viewportSize * 2.0 - 1.0; }

// The eye-space point of this pixel's centre on the plane at eye distance `eyeDistance`.
vec3 eyePointAt(float eyeDistance) { return eyePointAtNdc(fragmentNdc(), eyeDistance); }

// The voxel position this pixel's centre samples on this slice (quantized): along its ray for
// the MIP family (RAY_SAMPLING), else from the slice's coefficients.
vec3 sliceVoxel() {
#ifdef RAY_SAMPLING
  return rayVoxel(pixelRay(gl_FragCoord.xy), int(sliceIndex));
#elif defined(BOX_ALIGNED_SAMPLING)
  PixelRay ray = pixelRay(gl_FragCoord.xy);
  return boxAlignedVoxel(ray, boxPhase(ray), int(sliceIndex));
#else
  vec2 ndc = fragmentNdc();
  return quantizedVoxel(ndc.x * sliceVoxelPerNdcX + ndc.y * sliceVoxelPerNdcY +
                        sliceVoxelAtNdcOrigin);
#endif
}

#endif

#ifdef VSIL_COMPUTE_SHADER
// Pixel `pixel`'s centre in NDC, the same operations as fragmentNdc() on gl_FragCoord (the
// pixel + 0.5), so that a compute shader samples exactly where a slice pass does.
vec2 pixelNdc(ivec2 pixel) { return (vec2(pixel) + 0.5) / viewportSize * 2.0 - 1.0; }

// Pixel `pixel`'s centre in window coordinates: what gl_FragCoord.xy holds there (exact).
vec2 pixelCentre(ivec2 pixel) { return vec2(pixel) + 0.5; }

// The voxel position a pixel centre at `ndc` samples on a slice whose SliceBlock holds these
// coefficients (sliceVoxel()'s operations).
vec3 sliceVoxelAt(vec3 voxelPerNdcX, vec3 voxelPerNdcY, vec3 voxelAtNdcOrigin, vec2 ndc) {
  return quantizedVoxel(ndc.x * voxelPerNdcX + ndc.y * voxelPerNdcY + voxelAtNdcOrigin);
}
#endif

vec3 voxelFromEyePoint(vec3 eye) { return (voxelFromEye * vec4(eye, 1.0)).xyz; }

// Inside the volume's box, voxel coordinates -0.5 .. dims - 0.5.
bool insideVolume(vec3 voxel) {
  return all(greaterThanEqual(voxel, vec3(-0.5))) && all(lessThanEqual(voxel, volumeDims - 0.5));
}

// The texture coordinate of a (quantized) voxel position in this piece's brick textures.
vec3 brickTexCoord(vec3 voxel) { return (voxel - brickOrigin + 0.5) * brickTexPerVoxel; }

float sampleVolume(vec3 voxel) { return texture(volumeTexture, brickTexCoord(voxel)).r; }

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
