// march.comp (tiles pipeline): Nagy–Klein's footprint, contour and decision table for a range
// of slices (usually all) in one compute dispatch (shaders/tile_march.glsl), one workgroup per
// tile of MARCH_TILE_X x MARCH_TILE_Y pixels. Each invocation is a column of the tile plus one
// apron pixel below and above it; the group has one apron column on each side. Per slice an
// invocation samples its column (the alpha test) into a bit mask and puts it in shared memory;
// after a barrier it reads its two neighbours' masks, and the 8-neighbourhood test and the
// decision table run on all its own pixels at once as bit operations (silhouette.glsl
// decideBits). Pixels beyond the image are no neighbours, as in the slice passes' contour
// test: their footprint bits are set, so they never make a pixel CONTOUR.
// What is sampled: a pixel whose ray is inside occupied bricks (elsewhere its sample is below
// the iso value) and which has a busy own pixel in its 3x3 neighbourhood (elsewhere no decision
// depends on it); busy: not FILLED or SILHOUETTE (final), and not past where its ray leaves
// occupied bricks for good (mark_dead.frag's rule: its later contour values are all EMPTY). A
// tile starts at the first slice where one of its own rays enters occupied bricks and stops
// once no own pixel is busy. The extra empty slice and shading are finish_hits.frag's, as in
// the fast pipeline (a CONTOUR left at the end becomes SILHOUETTE there).
// In/out: own pixels' records (silhouette.glsl), between dispatches with a SILHOUETTE's depth
// still that of its first CONTOUR sample; the dispatch ending the march writes the finished one.
//
// Why it is shaped so (llvmpipe runs a group's invocations 8 lanes at a time, runs both sides of
// every branch but leaves a loop once all 8 lanes have, and reads shared memory lane by lane):
//  - a column per invocation: what is paid per slice besides sampling (the slice's uniforms,
//    the shared-memory exchange, the barrier, the decision table, the busy test) is paid once
//    per column, not per pixel; tall columns (30 own rows, one 32-bit mask with the apron) and
//    32 columns per group measured fastest (tile_march.h);
//  - the samples are a loop over the rows to sample, so that rows no lane needs cost nothing;
//  - one barrier per slice: the masks are double-buffered by the slice's parity, so the next
//    slice's stores cannot meet this slice's loads; whether any own pixel is still busy goes
//    through one shared word that busy invocations set to the slice index, read after the next
//    barrier, so the loop ends for the whole group at once (barriers stay in uniform control
//    flow);
//  - which rows are inside occupied bricks is decided for blocks of kBlock slices (a superset,
//    so still exact): per slice it cost more than the samples it saved.
layout(local_size_x = MARCH_GROUP_X) in;

const int kRows = MARCH_TILE_Y + 2;  // a column: the tile's rows and one apron row each side
const int kBlock = 4;

// Per column and slice parity: its footprint bits, and its own pixels busy after the slice
// before (any busy pixel in a neighbour column makes this column's rows next to it sampled).
shared uvec2 columns[2][MARCH_GROUP_X];
shared int lastBusySlice;

uint dilateRows(uint rows) { return rows | (rows << 1u) | (rows >> 1u); }

void main() {
  int column = int(gl_LocalInvocationID.x);
  ivec2 origin = tileOrigin();
  bool ownColumn = column >= 1 && column <= MARCH_TILE_X;
  // Row j of the column is pixel (x, origin.y + j - 1); rows 1 .. MARCH_TILE_Y are own pixels.
  int x = origin.x + column - 1;
  float entryDepth[kRows], exitDepth[kRows];
  float firstDepth[kRows], firstEye[kRows], contourDepth[kRows];
  uint own = 0u;
  uint beyondImage = 0u;  // rows of this column outside the image
  uint states[4] = uint[4](0u, 0u, 0u, 0u);  // bit j set in states[t]: row j's state is t
  float tileEntry = 1.0;
  for (int j = 0; j < kRows; ++j) {
    ivec2 pixel = ivec2(x, origin.y + j - 1);
    bool inside = insideImage(pixel);
    bool owned = inside && ownColumn && j >= 1 && j <= MARCH_TILE_Y;
    uint bit = 1u << uint(j);
    own |= owned ? bit : 0u;
    beyondImage |= inside ? 0u : bit;
    vec4 record = continuesMarch() && owned ? imageLoad(recordImage, pixel) : vec4(0.0);
    for (uint t = 0u; t < 4u; ++t) states[t] |= owned && uint(record.r) == t ? bit : 0u;
    firstDepth[j] = record.g;
    firstEye[j] = record.b;
    contourDepth[j] = record.a;
    // Outside the image: never inside [entry, exit), so never sampled: EMPTY.
    entryDepth[j] = inside ? entryDepthAt(pixel) : 1.0;
    exitDepth[j] = inside ? exitDepthAt(pixel) : 0.0;
    if (owned) tileEntry = min(tileEntry, entryDepth[j]);
  }
  if (gl_LocalInvocationIndex == 0u) lastBusySlice = -1;
  int first = tileFirstSlice(tileEntry);  // its barriers publish lastBusySlice too
  uint busy = states[STATE_EMPTY] | states[STATE_CONTOUR];
  uint neighboursBusy = ~0u;  // until the first exchange: anything
  bool done = false;
  for (int block = first; block < rangeEndSlice && !done; block += kBlock) {
    int blockEnd = min(block + kBlock, rangeEndSlice);
    // Rows whose ray is inside occupied bricks somewhere in this block, and rows not yet past
    // their exit at its start.
    float nearest = sliceWindowDepthAt(block), farthest = sliceWindowDepthAt(blockEnd - 1);
    uint inRange = 0u, beforeExit = 0u;
    for (int j = 0; j < kRows; ++j) {
      uint bit = 1u << uint(j);
      beforeExit |= nearest < exitDepth[j] ? bit : 0u;
      inRange |= nearest < exitDepth[j] && farthest > entryDepth[j] ? bit : 0u;
    }
    busy &= beforeExit;
    for (int k = block; k < blockEnd; ++k) {
      SliceParams slice = sliceAt(k);
      uint filled = 0u;
      for (uint rest = inRange & dilateRows(busy | neighboursBusy); rest != 0u;
           rest &= rest - 1u) {
        int j = findLSB(rest);
        vec3 voxel = sliceVoxelOf(slice, pixelNdc(ivec2(x, origin.y + j - 1)));
        filled |= insideVolume(voxel) && sampleVolume(voxel) >= isoValue ? 1u << uint(j) : 0u;
      }
      filled |= beyondImage;  // not EMPTY: they never make a neighbour CONTOUR
      int parity = k & 1;
      columns[parity][column] = uvec2(filled, busy);
      barrier();
      // Busy pixels of the previous slice wrote k - 1 before this barrier; none: all are done.
      if (k > first && lastBusySlice < k - 1) {
        done = true;
        break;
      }
      uvec2 left = columns[parity][max(column - 1, 0)];
      uvec2 right = columns[parity][min(column + 1, MARCH_GROUP_X - 1)];
      neighboursBusy = left.y | right.y;
      uint rows = left.x & filled & right.x;
      uint surrounded = rows & (rows << 1u) & (rows >> 1u);  // all 9 of the 3x3 around bit j
      uint contours[3] = uint[3](own & ~filled, own & filled & surrounded,
                                 own & filled & ~surrounded);  // EMPTY, FILLED, CONTOUR
      uint wasEmpty = states[STATE_EMPTY], wasContour = states[STATE_CONTOUR];
      decideBits(states, contours);
      // The record's depths (silhouette.glsl decideRecord), where something happened: the
      // first hit, and the latest CONTOUR sample when a run of them ends in a detection (a run
      // going on at the end of the range is settled below).
      for (uint rest = wasEmpty & ~states[STATE_EMPTY]; rest != 0u; rest &= rest - 1u) {
        int j = findLSB(rest);
        firstDepth[j] = slice.depth;
        firstEye[j] = slice.eyeDistance;
      }
      for (uint rest = wasContour & states[STATE_SILHOUETTE]; rest != 0u; rest &= rest - 1u) {
        contourDepth[findLSB(rest)] = previousSliceDepthAt(k);
      }
      busy = (states[STATE_EMPTY] | states[STATE_CONTOUR]) & beforeExit;
      if (busy != 0u) lastBusySlice = k;
    }
  }
  // A CONTOUR record now was CONTOUR on every slice since it turned so (any other contour value
  // ends the run), the last of this range included: the loop cannot have ended before, since a
  // CONTOUR sample leaves its pixel busy.
  float lastDepth = sliceDepthAt(max(rangeEndSlice - 1, rangeFirstSlice));
  for (int j = 1; j <= MARCH_TILE_Y; ++j) {
    uint bit = 1u << uint(j);
    if ((own & bit) == 0u) continue;
    uint state = STATE_EMPTY;
    for (uint t = 1u; t < 4u; ++t) state = (states[t] & bit) != 0u ? t : state;
    vec4 record = vec4(float(state), firstDepth[j], firstEye[j], contourDepth[j]);
    if (state == STATE_CONTOUR) record.a = lastDepth;
    if (endsMarch() && state == STATE_SILHOUETTE) record.g = silhouetteDepth(record);
    imageStore(recordImage, ivec2(x, origin.y + j - 1), record);
  }
}
