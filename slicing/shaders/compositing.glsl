// compositing.glsl: what front-to-back compositing slice passes share (slicing/compositing.h;
// illustrate, and the DVR composite of mip and semantic next). A pass writes one premultiplied
// sample per pixel; the blending (ONE_MINUS_DST_ALPHA, ONE) puts it behind what the slices in
// front accumulated.

// Δ/Δ₀: the slice distance in voxels along the view (SlicePlan::stepVoxels). Opacities are given
// per voxel (Δ₀ = one voxel), so --sampling 2 draws twice the slices at half the opacity each
// and the image stays the same.
uniform float opacityExponent;

// The premultiplied sample for a straight colour (clamped to [0, 1]) and an opacity per voxel:
// α = 1 − (1 − o)^(Δ/Δ₀), o clamped to [0, 1].
vec4 compositedSample(vec3 color, float opacity) {
  float alpha = 1.0 - pow(1.0 - clamp(opacity, 0.0, 1.0), opacityExponent);
  return vec4(clamp(color, 0.0, 1.0) * alpha, alpha);
}
