// tile_march.glsl: what the tile-marching compute shaders share (slicing/tile_march.h), after
// common.glsl and hit_records.glsl. A march is one compute dispatch per range of slices (often
// one for the whole frame), one workgroup per screen tile of MARCH_TILE_X x MARCH_TILE_Y pixels;
// each shader lays its invocations over its tile (and an apron, where it needs neighbours) its
// own way, samples its pixels on slice after slice, front to back, exactly where a slice pass
// samples them (pixelNdc and sliceVoxelAt, or pixelCentre and rayVoxel for the MIP family's
// RAY_SAMPLING; sampleVolume), and keeps their records in registers.
// In: this dispatch's slices (SliceRange), where rays enter occupied bricks (entry depth image)
// and leave them for good (exit depth image; slicing/empty_space.h).
// In/out: the records, through recordImage: read at the start of a dispatch that continues
// another, written at its end.
#ifndef SLICE_STRIDE_VEC4
#error "tile marches need SLICE_STRIDE_VEC4 and MARCH_RANGE_SLICES (tile_march.h marchProgram)"
#endif

// Slices [rangeFirstSlice, rangeFirstSlice + MARCH_RANGE_SLICES) as one uniform block
// (frame_uniforms.h bindSliceRange): slice k's SliceBlock (common.glsl) from vec4
// (k - rangeFirstSlice) * SLICE_STRIDE_VEC4 on. A uniform block, not a storage buffer: llvmpipe
// reads storage buffers lane by lane behind branches, uniform blocks with one gather.
layout(std140, binding = 2) uniform SliceRange {
  vec4 sliceWords[MARCH_RANGE_SLICES * SLICE_STRIDE_VEC4];
};
uniform int rangeFirstSlice;
uniform int rangeEndSlice;  // this dispatch marches slices [rangeFirstSlice, rangeEndSlice)
uniform int sliceCount;     // the frame's: the dispatch ending there finishes the records

struct SliceParams {
  vec3 voxelPerNdcX;
  float eyeDistance;
  vec3 voxelPerNdcY;
  float depth;
  vec3 voxelAtNdcOrigin;
  float windowDepth;
};

int sliceWord(int k) { return (k - rangeFirstSlice) * SLICE_STRIDE_VEC4; }

SliceParams sliceAt(int k) {
  int word = sliceWord(k);
  vec4 a = sliceWords[word], b = sliceWords[word + 1], c = sliceWords[word + 2];
  return SliceParams(a.xyz, a.w, b.xyz, b.w, c.xyz, c.w);
}

float sliceEyeDistanceAt(int k) { return sliceWords[sliceWord(k)].w; }
float sliceDepthAt(int k) { return sliceWords[sliceWord(k) + 1].w; }
float sliceWindowDepthAt(int k) { return sliceWords[sliceWord(k) + 2].w; }
float previousSliceDepthAt(int k) { return sliceWords[sliceWord(k) + 3].x; }

vec3 sliceVoxelOf(SliceParams s, vec2 ndc) {
  return sliceVoxelAt(s.voxelPerNdcX, s.voxelPerNdcY, s.voxelAtNdcOrigin, ndc);
}

layout(binding = UNIT_ENTRY_DEPTH) uniform sampler2D entryDepthTexture;
layout(binding = UNIT_EXIT_DEPTH) uniform sampler2D exitDepthTexture;
layout(binding = IMAGE_RECORD, rgba32f) uniform restrict image2D recordImage;

bool continuesMarch() { return rangeFirstSlice > 0; }
bool endsMarch() { return rangeEndSlice >= sliceCount; }

// Pixels of the tile are GL's (rows bottom-up, as gl_FragCoord); some lie outside the image.
ivec2 tileOrigin() { return ivec2(gl_WorkGroupID.xy) * ivec2(MARCH_TILE_X, MARCH_TILE_Y); }

bool insideImage(ivec2 pixel) {
  return all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, ivec2(viewportSize)));
}

// Where the pixel's ray enters occupied bricks (window depth; 1 where it never does).
float entryDepthAt(ivec2 pixel) { return texelFetch(entryDepthTexture, pixel, 0).r; }

// The window depth past which the pixel's ray meets no occupied brick: from a slice there on,
// its samples stay below the iso value (0 where the ray meets none; mark_dead.frag's rule).
float exitDepthAt(ivec2 pixel) { return texelFetch(exitDepthTexture, pixel, 0).r; }

// The first slice from `from` on (up to rangeEndSlice) whose window depth exceeds
// `windowDepth` (or reaches it, with `orEqual`): slices come in depth order.
int firstSliceBeyond(int from, float windowDepth, bool orEqual) {
  int low = from, high = rangeEndSlice;
  while (low < high) {
    int middle = (low + high) / 2;
    float depth = sliceWindowDepthAt(middle);
    if (depth > windowDepth || (orEqual && depth == windowDepth)) {
      high = middle;
    } else {
      low = middle + 1;
    }
  }
  return low;
}
int firstSliceBeyond(int from, float windowDepth) {
  return firstSliceBeyond(from, windowDepth, false);
}

// The slices [first, end) of this range a pixel's ray samples: beyond where it enters occupied
// bricks (a slice pass's GREATER test against the entry depth) and before where it leaves them
// for good (from the exit depth on its samples stay below the technique's threshold:
// mark_dead.frag's rule). Two searches per pixel instead of two depth tests per sample.
struct SliceSpan {
  int first;
  int end;
};
SliceSpan sliceSpan(int from, float entryDepth, float exitDepth) {
  int first = firstSliceBeyond(from, entryDepth);
  return SliceSpan(first, max(first, firstSliceBeyond(first, exitDepth, true)));
}

shared uint tileEntryBits;

// The first slice of this dispatch's range that any own pixel of the tile samples (a slice pass
// testing GREATER against the entry depth samples the slices beyond it), rangeEndSlice if none.
// `entryDepth` is the smallest entry depth of this invocation's own pixels (1 for none). Every
// invocation of the group calls it (it holds barriers).
int tileFirstSlice(float entryDepth) {
  if (gl_LocalInvocationIndex == 0u) tileEntryBits = floatBitsToUint(1.0);
  barrier();
  // Depths are >= 0, where the order of floats and of their bits agree.
  atomicMin(tileEntryBits, floatBitsToUint(entryDepth));
  barrier();
  return firstSliceBeyond(rangeFirstSlice, uintBitsToFloat(tileEntryBits));
}

