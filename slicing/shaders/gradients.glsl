// gradients.glsl: the gradient texture (slicing/gradient_texture.h) for the slice passes that
// shade by it (illustrate, semantic). A texel holds g/max|g| and, with GRADIENTS_HOLD_VALUES,
// the voxel's value as well (the volume's texels are exact in half floats): then one trilinear
// fetch gives a visible sample its value and its gradient, where it otherwise takes two (the
// volume, then the gradients), and llvmpipe pays most of a fetch in its addressing.

layout(binding = UNIT_GRADIENT) uniform sampler3D gradientTexture;

// The value of the sample at a voxel position. With GRADIENTS_HOLD_VALUES, `fetched` receives
// the texel it came from, for gradientAt.
float sampleValue(vec3 voxel, out vec4 fetched) {
#ifdef GRADIENTS_HOLD_VALUES
  fetched = texture(gradientTexture, brickTexCoord(voxel));
  return fetched.a;
#else
  fetched = vec4(0.0);
  return sampleVolume(voxel);
#endif
}

// g/max|g| at the voxel position (trilinear): `fetched` from sampleValue where it holds it.
vec3 gradientAt(vec3 voxel, vec4 fetched) {
#ifdef GRADIENTS_HOLD_VALUES
  return fetched.xyz;
#else
  return texture(gradientTexture, brickTexCoord(voxel)).xyz;
#endif
}

// The unit direction of a stored gradient (0 where it vanishes) and its magnitude |∇f|/max|∇f|
// (clamped to 1: interpolation and half floats may overshoot it by an ulp). False where the
// gradient vanishes and so has no direction.
bool splitGradient(vec3 g, out vec3 direction, out float magnitude) {
  float length2 = dot(g, g);
  float inverseLength = length2 > 0.0 ? inversesqrt(length2) : 0.0;
  direction = g * inverseLength;
  magnitude = min(length2 * inverseLength, 1.0);
  return length2 > 0.0;
}
