// slice.vert: a slice polygon (box ∩ plane), vertices in voxel coordinates, projected by the
// frame's clipFromVoxel (common.glsl).
// Fragment shaders recompute their sample point from gl_FragCoord (common.glsl), so the
// polygon only decides which pixels run.
layout(location = 0) in vec3 positionVoxel;
// Passes of one slice compare depths for equality: the same polygon must rasterize the same.
invariant gl_Position;

void main() { gl_Position = clipFromVoxel * vec4(positionVoxel, 1.0); }
