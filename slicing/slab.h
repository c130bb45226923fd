#pragma once
// A volume split into slabs of z across processes (`mpirun -np N vsil render`, src/mpi/):
// what one process holds of it, and how the processes pass a frame's targets along.
//
// The slabs are runs of the whole volume's bricks along z (core/brick_layout.h): a process
// uploads only the bricks it holds (its own and, as ghost layers, as many brick layers on each
// side as the technique's ghost width for the view needs, techniqueGhostVoxels), draws only the
// slice pieces of the bricks it owns, and the pieces of its ghost bricks where a technique reads
// neighbouring pixels of the same slice (silhouette's footprint for the contour test).
// Bricks sample exactly alike in any texture, so a process's samples are the single process's
// samples. Slab borders are brick planes z = b − 0.5; a sample belongs to the slab its point's z
// lies in (the first and last slab reach to ∓infinity, as bricks do).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/brick_layout.h"
#include "core/camera.h"
#include "core/composition.h"
#include "core/options.h"
#include "core/volume.h"
#include "slicing/gl_objects.h"

namespace vsil {

struct TechniqueInfo;

// One pixel of a slab's silhouette run (Composition::PairReduce), as it travels between the
// processes: composition::NkRun with plain fields, plus what the run's samples cannot say
// themselves. Floats and ints only, so that an array of them is one MPI datatype.
struct PairPixel {
  // The run's first sample's PixelState; -1 for a run without samples inside the volume (those
  // outside are EMPTY: the slice gap below accounts for them).
  std::int32_t first = -1;
  std::int32_t t = 0;                       // NkRun::t
  float hit = 0, detectPrev = 0, last = 0;  // NkRun's depths
  // Travel with the hit (where the state's first non-EMPTY sample lies): the first-hit eye
  // distance and the shade there (finish_hits.frag), from the process that owns the hit.
  float eyeDistance = 0, shade = 0;
  // The first and last slice index of the run's samples inside the volume (-1 without): a gap
  // between two runs' slices is samples outside the volume, EMPTY.
  std::int32_t firstSlice = -1, lastSlice = -1;
  // rayZDirection of the pixel: +1 where the process of lower z is in front, -1 where it is
  // behind, 0 (the ray stays in one slab) either way.
  std::int32_t zDirection = 0;
};
composition::NkRun runOf(const PairPixel& pixel);
// `lowerZ`'s run combined with `higherZ`'s, in the order the pixel's ray meets them (core/
// composition.h combine; an EMPTY sample between runs whose slices leave a gap); the result
// spans both slabs.
PairPixel combineInZOrder(const PairPixel& lowerZ, const PairPixel& higherZ);

// Moves a frame's targets between the processes in the view's depth order (a relay): the
// process nearest the eye starts, each continues from what the one in front of it sent.
class SlabRelay {
 public:
  virtual ~SlabRelay() = default;
  // Orders the processes for receive/send/shareLast by the frame's z direction
  // (frameZDirection): +1 the slab of lowest z first, -1 the highest first, 0 either. nullopt
  // (a perspective view whose rays leave the eye both ways along z, so that no order of the
  // slabs is every ray's order) refuses, alike on every process.
  virtual void orderByDepth(std::optional<int> zDirection) = 0;
  // Wall milliseconds spent in this relay's calls so far (the transfers, the waits for the
  // other processes, the read-backs they need): the renderer reports a frame's share as
  // RenderTimings::combine. An implementation adds each call's time to busyMs_.
  double busyMs() const { return busyMs_; }
  // Replaces the colour of `targets` with what the process in front sent (nothing on the first).
  virtual void receive(const std::vector<const gl::RenderTarget*>& targets) = 0;
  // Sends `targets` to the process behind (nothing on the last).
  virtual void send(const std::vector<const gl::RenderTarget*>& targets) = 0;
  // The same for the depth-stencil buffer of `target` (the bits as they are).
  virtual void receiveDepthStencil(const gl::RenderTarget& target) = 0;
  virtual void sendDepthStencil(const gl::RenderTarget& target) = 0;
  // The last process's `targets` to every process.
  virtual void shareLast(const std::vector<const gl::RenderTarget*>& targets) = 0;
  // Replaces every float of `target` by its maximum over all processes (Composition::MaxReduce:
  // float max is exact and commutative, so the order does not matter).
  virtual void maxReduce(const gl::RenderTarget& target) = 0;
  // The largest `value` over all processes, on every process (the volume's largest gradient).
  virtual float maxOverProcesses(float value) = 0;
  // Replaces `pixels` on the process of the lowest z by the combine of every process's pixels
  // in z order (combineInZOrder; the others' `pixels` are left unspecified): the silhouette
  // pair (Composition::PairReduce).
  virtual void pairReduce(std::vector<PairPixel>& pixels) = 0;

 protected:
  double busyMs_ = 0;
};

// The first brick of layer z (Brick::index.z; every brick of a layer has its z bounds).
const Brick& brickOfLayer(const BrickLayout& layout, int z);
// The first voxel z that layer `layer` owns (high: the end of its voxels), cut to the volume,
// as VolumeTexture::readVoxels counts them.
int layerVoxelZ(const BrickLayout& layout, int layer, bool high, int dimsZ);
// The voxels z that layers [z0, z1) own, [first, end), cut to the volume (layerVoxelZ of each
// end).
std::array<int, 2> layersVoxels(const BrickLayout& layout, int z0, int z1, int dimsZ);

// Slabs along z meet a ray in z order: which way the ray through `pixel` (pixel coordinates, a
// centre at +0.5) runs along the volume's z, +1 towards higher z, -1 towards lower, 0 along a
// plane of constant z (it never leaves its slab, so any order is its order).
int rayZDirection(const View& view, glm::dvec2 pixel);

// The direction every ray of the frame shares (orthographic views; a perspective eye outside
// the slabs' z), or nullopt where rays leave the eye both ways along z. The ray's z
// direction is affine in the pixel, so the four corner pixels decide.
std::optional<int> frameZDirection(const View& view);

// How far apart, in voxels along z, the points of one slice plane for neighbouring pixels
// (diagonal ones too) lie, at the slice farthest from the eye, where a perspective pixel is
// widest: one pixel's footprint along z.
double pixelFootprintVoxelsZ(const View& view, glm::ivec3 dims);

// The ghost width, in voxels along z, of a slab of `technique`'s frames with the `given` options
// and the frame's view: TechniqueInfo::slabGhostVoxels (0 where unset). A process holds that
// many voxels of ghost bricks beyond the slab it owns (mpi/slab_render.h readSlab), so that it
// draws or reads those samples itself. The test hook VSIL_SLAB_GHOST_VOXELS (an environment
// variable, read here only), when set, replaces the width (for tests that show what too thin a
// ghost layer breaks: tests/mpi/mpi_silhouette_test.sh).
int techniqueGhostVoxels(const TechniqueInfo& technique, const OptionValues& given,
                         const View& view, glm::ivec3 dims);

struct SlabPart {
  glm::ivec3 dims{0};            // the whole volume's
  BrickLayout layout;            // the whole volume's bricks
  int ownedZ0 = 0, ownedZ1 = 0;  // brick layers (Brick::index.z) this process owns, [z0, z1)
  int heldZ0 = 0, heldZ1 = 0;    // and holds: owned plus the ghost layers
  int voxelZ0 = 0;               // the whole volume's z of the slab volume's z = 0
  GLenum internalFormat = 0;     // the same on every process (R16F only where all slabs allow it)
  ValueRange valueRange;         // the whole volume's
  DerivedDefaults derived;       // the whole volume's (summed histograms)
  SlabRelay* relay = nullptr;

  bool owns(std::size_t brick) const {
    const int z = layout.bricks()[brick].index.z;
    return z >= ownedZ0 && z < ownedZ1;
  }
  bool holds(std::size_t brick) const {
    const int z = layout.bricks()[brick].index.z;
    return z >= heldZ0 && z < heldZ1;
  }
  // The sample positions (voxel z) the owned bricks own: [low, high) (±1e30 at the volume's
  // ends, as bricks have them).
  double ownedLowZ() const;
  double ownedHighZ() const;
  // The voxels z they own, [first, end), cut to the volume (layersVoxels).
  std::array<int, 2> ownedVoxels() const;
  // The voxels z the held bricks own (ghost layers too), [first, end), cut to the volume.
  std::array<int, 2> heldVoxels() const;
  // Voxel z the ghost layers reach beyond the owned bricks on the thinner side (0 without).
  int ghostVoxels() const;
};

}  // namespace vsil
