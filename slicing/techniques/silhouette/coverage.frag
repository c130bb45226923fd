// coverage.frag (silhouette, a slab's fast pipeline): where the slab owns a sample of the slice.
// Drawn over the slab's own pieces with MIN blending into a target cleared to a large value:
// (first slice, -last slice, first slice's depth, -last slice's depth) of the pixel's samples
// inside the volume that this process owns (silhouette_technique.cpp combineSlabs).
layout(location = 0) out vec4 coverage;

void main() {
  coverage = vec4(float(sliceIndex), -float(sliceIndex), sliceDepth, -sliceDepth);
}
