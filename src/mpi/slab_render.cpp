#include "mpi/slab_render.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>

#include "core/clock.h"
#include "core/error.h"
#include "mpi/mpi_world.h"
#include "slicing/gl.h"
#include "slicing/volume_texture.h"

namespace vsil::mpi {
namespace {

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

// Adds the wall time from its construction to its end to `busyMs` (SlabRelay::busyMs).
class BusyTimer {
 public:
  explicit BusyTimer(double& busyMs) : busyMs_(busyMs) {}
  BusyTimer(const BusyTimer&) = delete;
  BusyTimer& operator=(const BusyTimer&) = delete;
  ~BusyTimer() { busyMs_ += millisecondsSince(start_); }

 private:
  double& busyMs_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

class MpiRelay : public SlabRelay {
 public:
  void receive(const std::vector<const gl::RenderTarget*>&) override { unsupported(); }
  void send(const std::vector<const gl::RenderTarget*>&) override { unsupported(); }
  void shareLast(const std::vector<const gl::RenderTarget*>&) override { unsupported(); }

  void maxReduce(const gl::RenderTarget& target) override {
    const BusyTimer timer(busyMs_);
    if (target.internalFormat() != GL_R32F) {
      throw std::logic_error("MpiRelay::maxReduce: only R32F targets");
    }
    const glm::ivec2 size = target.size();
    std::vector<float> values(std::size_t(size.x) * std::size_t(size.y));
    VSIL_GL(glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer()));
    VSIL_GL(glReadBuffer(GL_COLOR_ATTACHMENT0));
    VSIL_GL(glPixelStorei(GL_PACK_ALIGNMENT, 1));
    VSIL_GL(glReadPixels(0, 0, size.x, size.y, GL_RED, GL_FLOAT, values.data()));
    check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_FLOAT, MPI_MAX,
                        MPI_COMM_WORLD),
          "MPI_Allreduce (max)");
    VSIL_GL(glBindTexture(GL_TEXTURE_2D, target.texture()));
    VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
    VSIL_GL(glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, size.x, size.y, GL_RED, GL_FLOAT,
                            values.data()));
    VSIL_GL(glBindTexture(GL_TEXTURE_2D, 0));
  }

 private:
  [[noreturn]] static void unsupported() {
    throw UnavailableError("the relay between MPI ranks is not available yet");
  }
};

// Bytes per texel the layout is chosen for, from the file's type alone (every rank alike): the
// format of the textures is agreed after reading.
std::size_t layoutTexelBytes(SampleType type) {
  return type == SampleType::UInt8 || type == SampleType::Int8 ? 2 : 4;
}

const Brick& layerBrick(const BrickLayout& layout, int z) {
  const glm::ivec3 counts = layout.counts();
  return layout.bricks()[std::size_t(z) * std::size_t(counts.x) * std::size_t(counts.y)];
}

// The layer's own voxels along z: [low + 0.5, high + 0.5) cut to the volume.
std::array<int, 2> ownVoxels(const BrickLayout& layout, int z0, int z1, int dimsZ) {
  const double low = std::max(layerBrick(layout, z0).low.z, -0.5);
  const double high = std::min(layerBrick(layout, z1 - 1).high.z, dimsZ - 0.5);
  return {int(low + 0.5), int(high + 0.5)};
}

}  // namespace

std::vector<double> gatherOnRoot(double value) {
  std::vector<double> all(rank() == 0 ? std::size_t(size()) : 0);
  check(MPI_Gather(&value, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD),
        "MPI_Gather");
  return all;
}

SlabRead readSlab(const std::string& spec, LoadOptions load, std::uint64_t maxTextureBytes) {
  if (!load.region.whole()) {
    throw EveryRankError("--crop, --stride: not combined with mpirun yet; crop the file first");
  }
  const int ranks = size(), me = rank();
  // The file's dimensions and type from its header and one slice.
  LoadOptions probe = load;
  probe.progress = nullptr;
  probe.region.crop = std::array<ReadRegion::Range, 3>{
      ReadRegion::Range{}, ReadRegion::Range{}, ReadRegion::Range{0, 1}};
  const Volume first = loadVolume(spec, probe);
  const glm::ivec3 dims = first.subset ? first.subset->fileDims : first.dims;

  GLint maxSide = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
  BrickLayout chosen =
      BrickLayout::choose(dims, layoutTexelBytes(first.type()), maxTextureBytes, maxSide);
  glm::ivec3 storage = chosen.bricks()[0].size;
  BrickLayout layout = BrickLayout::withStorage(dims, storage);
  // At least one brick layer per rank: smaller bricks along z (8 texels at least).
  while (layout.counts().z < ranks && storage.z > 8) {
    storage.z /= 2;
    layout = BrickLayout::withStorage(dims, storage);
  }
  const int layers = layout.counts().z;
  if (layers < ranks) {
    throw EveryRankError(spec + ": " + std::to_string(dims.z) + " slices make " +
                         std::to_string(layers) + " brick layers, fewer than the " +
                         std::to_string(ranks) + " ranks; run fewer ranks");
  }
  SlabRead read;
  SlabPart& part = read.part;
  part.dims = dims;
  part.layout = layout;
  part.ownedZ0 = me * layers / ranks;
  part.ownedZ1 = (me + 1) * layers / ranks;
  part.heldZ0 = part.ownedZ0;  // mip reads no neighbours: no ghost layers
  part.heldZ1 = part.ownedZ1;
  part.voxelZ0 = layerBrick(layout, part.heldZ0).origin.z;
  const Brick& lastHeld = layerBrick(layout, part.heldZ1 - 1);
  const int voxelZ1 = std::min(lastHeld.origin.z + lastHeld.size.z, dims.z);
  for (int r = 0; r < ranks; ++r) {
    read.slabs.push_back(
        ownVoxels(layout, r * layers / ranks, (r + 1) * layers / ranks, dims.z));
  }

  LoadOptions slabLoad = load;
  slabLoad.region.crop = std::array<ReadRegion::Range, 3>{
      ReadRegion::Range{}, ReadRegion::Range{}, ReadRegion::Range{part.voxelZ0, voxelZ1}};
  read.volume = loadVolume(spec, slabLoad);

  // What every rank must agree on: the texture format, the value range, the derived defaults.
  int wide = textureFormatFor(read.volume) == GL_R32F ? 1 : 0;
  check(MPI_Allreduce(MPI_IN_PLACE, &wide, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  part.internalFormat = wide ? GL_R32F : GL_R16F;
  const ValueRange mine = valueRange(read.volume);
  float low = mine.min, high = mine.max;
  check(MPI_Allreduce(MPI_IN_PLACE, &low, 1, MPI_FLOAT, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
  check(MPI_Allreduce(MPI_IN_PLACE, &high, 1, MPI_FLOAT, MPI_MAX, MPI_COMM_WORLD),
        "MPI_Allreduce");
  part.valueRange = {low, high};
  const std::array<int, 2> own = read.slabs[std::size_t(me)];
  LevelCounts counts = levelCounts(read.volume, part.valueRange, own[0] - part.voxelZ0,
                                   own[1] - part.voxelZ0);
  check(MPI_Allreduce(MPI_IN_PLACE, counts.data(), int(counts.size()), MPI_UINT64_T, MPI_SUM,
                      MPI_COMM_WORLD),
        "MPI_Allreduce");
  part.derived = derivedDefaultsFromCounts(part.valueRange, counts);
  read.relay = std::make_unique<MpiRelay>();
  part.relay = read.relay.get();
  return read;
}

}  // namespace vsil::mpi
