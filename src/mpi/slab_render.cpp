#include "mpi/slab_render.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>
#include <sstream>
#include <string_view>

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

// The relay (Composition::Relay) over a communicator of the ranks in the frame's depth order;
// the floats travel as read back, so the next rank continues from the very bits.
class MpiRelay : public SlabRelay {
 public:
  ~MpiRelay() override { freeDepthOrder(); }

  void orderByDepth(std::optional<int> zDirection) override {
    if (!zDirection) {
      throw EveryRankError(
          "--view, --zoom: this perspective view has rays that leave the eye both ways along "
          "the volume's z, so no order of the z slabs is every ray's order; use --ortho, "
          "another view (a higher or lower --view elevation, or --up +y) or one rank");
    }
    // Rank r owns the r-th slab from low z (readSlab): the key is its place along the rays.
    const int key = *zDirection < 0 ? size() - 1 - rank() : rank();
    freeDepthOrder();
    check(MPI_Comm_split(MPI_COMM_WORLD, 0, key, &depthOrder_), "MPI_Comm_split");
    check(MPI_Comm_rank(depthOrder_, &place_), "MPI_Comm_rank");
    check(MPI_Comm_size(depthOrder_, &count_), "MPI_Comm_size");
  }

  void receive(const std::vector<const gl::RenderTarget*>& targets) override {
    const BusyTimer timer(busyMs_);
    if (place() == 0) return;
    for (const gl::RenderTarget* target : targets) {
      std::vector<float> values = target->readFloats();  // sized alike; overwritten
      check(MPI_Recv(values.data(), int(values.size()), MPI_FLOAT, place_ - 1, 0, depthOrder_,
                     MPI_STATUS_IGNORE),
            "MPI_Recv (relay)");
      target->writeFloats(values);
    }
  }

  void send(const std::vector<const gl::RenderTarget*>& targets) override {
    const BusyTimer timer(busyMs_);
    if (place() == count_ - 1) return;
    for (const gl::RenderTarget* target : targets) {
      const std::vector<float> values = target->readFloats();
      check(MPI_Send(values.data(), int(values.size()), MPI_FLOAT, place_ + 1, 0, depthOrder_),
            "MPI_Send (relay)");
    }
  }

  void shareLast(const std::vector<const gl::RenderTarget*>& targets) override {
    const BusyTimer timer(busyMs_);
    place();
    for (const gl::RenderTarget* target : targets) {
      std::vector<float> values = target->readFloats();
      check(MPI_Bcast(values.data(), int(values.size()), MPI_FLOAT, count_ - 1, depthOrder_),
            "MPI_Bcast (relay)");
      if (place_ != count_ - 1) target->writeFloats(values);
    }
  }

  void receiveDepthStencil(const gl::RenderTarget& target) override {
    if (place() == 0) return;
    const glm::ivec2 size = target.size();
    std::vector<std::uint32_t> bits(std::size_t(size.x) * std::size_t(size.y));
    check(MPI_Recv(bits.data(), int(bits.size()), MPI_UINT32_T, place_ - 1, 1, depthOrder_,
                   MPI_STATUS_IGNORE),
          "MPI_Recv (relay depth)");
    // Into the target's renderbuffer: through a texture of the same format and a blit, which
    // copies depth and stencil bits unchanged.
    gl::TextureName staging = gl::createTexture();
    VSIL_GL(glBindTexture(GL_TEXTURE_2D, staging.id()));
    VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 4));
    VSIL_GL(glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH24_STENCIL8, size.x, size.y, 0, GL_DEPTH_STENCIL,
                         GL_UNSIGNED_INT_24_8, bits.data()));
    VSIL_GL(glBindTexture(GL_TEXTURE_2D, 0));
    gl::FramebufferName from = gl::createFramebuffer();
    VSIL_GL(glBindFramebuffer(GL_READ_FRAMEBUFFER, from.id()));
    VSIL_GL(glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
                                   staging.id(), 0));
    VSIL_GL(glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer()));
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    VSIL_GL(glBlitFramebuffer(0, 0, size.x, size.y, 0, 0, size.x, size.y,
                              GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, GL_NEAREST));
    if (scissor) glEnable(GL_SCISSOR_TEST);
    VSIL_GL(glBindFramebuffer(GL_FRAMEBUFFER, 0));
  }

  void sendDepthStencil(const gl::RenderTarget& target) override {
    if (place() == count_ - 1) return;
    const glm::ivec2 size = target.size();
    std::vector<std::uint32_t> bits(std::size_t(size.x) * std::size_t(size.y));
    VSIL_GL(glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer()));
    VSIL_GL(glPixelStorei(GL_PACK_ALIGNMENT, 4));
    VSIL_GL(
        glReadPixels(0, 0, size.x, size.y, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, bits.data()));
    check(MPI_Send(bits.data(), int(bits.size()), MPI_UINT32_T, place_ + 1, 1, depthOrder_),
          "MPI_Send (relay depth)");
  }

  float maxOverProcesses(float value) override {
    check(MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_FLOAT, MPI_MAX, MPI_COMM_WORLD),
          "MPI_Allreduce (max)");
    return value;
  }

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
    VSIL_GL(
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, size.x, size.y, GL_RED, GL_FLOAT, values.data()));
    VSIL_GL(glBindTexture(GL_TEXTURE_2D, 0));
  }

  void pairReduce(std::vector<PairPixel>& pixels) override {
    const BusyTimer timer(busyMs_);
    // The slabs are in z order by rank (readSlab) and every pixel's ray meets them in z order,
    // up or down (slab.h rayZDirection): a reduce in rank order with a non-commutative operator
    // that orients each pixel by its own direction is exact for every view, also perspective
    // views whose rays run both ways in one frame, with no communicator per frame direction.
    MPI_Datatype pixel = MPI_DATATYPE_NULL;
    check(MPI_Type_contiguous(int(sizeof(PairPixel)), MPI_BYTE, &pixel), "MPI_Type_contiguous");
    check(MPI_Type_commit(&pixel), "MPI_Type_commit");
    MPI_Op op = MPI_OP_NULL;
    check(MPI_Op_create(&combinePairs, /*commute=*/0, &op), "MPI_Op_create");
    std::vector<PairPixel> combined(rank() == 0 ? pixels.size() : 0);
    const int code = MPI_Reduce(pixels.data(), combined.data(), int(pixels.size()), pixel, op, 0,
                                MPI_COMM_WORLD);
    MPI_Op_free(&op);
    MPI_Type_free(&pixel);
    check(code, "MPI_Reduce (silhouette pairs)");
    if (rank() == 0) pixels = std::move(combined);
  }

 private:
  // MPI's user function: inout[i] = in[i] ∘ inout[i], `in` from the lower ranks (lower z).
  static void combinePairs(void* in, void* inout, int* count, MPI_Datatype*) {
    const auto* lower = static_cast<const PairPixel*>(in);
    auto* higher = static_cast<PairPixel*>(inout);
    for (int i = 0; i < *count; ++i) higher[i] = combineInZOrder(lower[i], higher[i]);
  }

  int place() const {
    if (depthOrder_ == MPI_COMM_NULL) throw std::logic_error("MpiRelay: relay before orderByDepth");
    return place_;
  }
  void freeDepthOrder() {
    if (depthOrder_ != MPI_COMM_NULL) MPI_Comm_free(&depthOrder_);
  }

  MPI_Comm depthOrder_ = MPI_COMM_NULL;
  int place_ = 0, count_ = 0;  // this rank's place along the rays, of count_
};

// Bytes per texel the layout is chosen for, from the file's type alone (every rank alike): the
// format of the textures is agreed after reading.
std::size_t layoutTexelBytes(SampleType type) {
  return type == SampleType::UInt8 || type == SampleType::Int8 ? 2 : 4;
}

// A read every rank makes before its next collective: a file error on any rank (a bad file
// every rank reads alike, or a part of it one rank alone reads) is said once, by rank 0, and
// every rank stops alike (refuseAlike), where each rank aborted with its own line and
// MPI_Abort's banner.
Volume loadAlike(const std::string& spec, const LoadOptions& load) {
  std::optional<Volume> volume;
  std::optional<std::string> refusal;
  try {
    volume = loadVolume(spec, load);
  } catch (const InputError& e) {
    refusal = e.what();
  }
  refuseAlike(refusal);
  return std::move(*volume);
}

}  // namespace

std::vector<double> gatherOnRoot(double value) {
  std::vector<double> all(rank() == 0 ? std::size_t(size()) : 0);
  check(MPI_Gather(&value, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD),
        "MPI_Gather");
  return all;
}

Volume probeSlab(const std::string& spec, LoadOptions load) {
  if (!load.region.whole()) {
    throw EveryRankError("--crop, --stride: not combined with mpirun yet; crop the file first");
  }
  load.progress = nullptr;
  load.region.crop = std::array<ReadRegion::Range, 3>{ReadRegion::Range{}, ReadRegion::Range{},
                                                      ReadRegion::Range{0, 1}};
  return loadAlike(spec, load);
}

glm::ivec3 fileDims(const Volume& probe) {
  return probe.subset ? probe.subset->fileDims : probe.dims;
}

SlabRead readSlab(const std::string& spec, LoadOptions load, std::uint64_t maxTextureBytes,
                  int ghostVoxels) {
  const int ranks = size(), me = rank();
  // The file's dimensions and type from its header and one slice.
  const Volume first = probeSlab(spec, load);
  const glm::ivec3 dims = fileDims(first);
  // The command lines agree (requireSameCommand), but one path may name different files on
  // different ranks (another working directory, a node's stale copy), whose slabs would
  // combine into a picture of neither: the file's size, type, spacing and first slice must
  // be rank 0's.
  const std::string fingerprint = first.visit([&](auto samples) {
    const std::string_view bytes(reinterpret_cast<const char*>(samples.data()),
                                 samples.size_bytes());
    std::ostringstream text;
    text << dims.x << "x" << dims.y << "x" << dims.z << " " << sampleTypeName(first.type()) << " "
         << first.spacing.x << "," << first.spacing.y << "," << first.spacing.z << " "
         << std::hash<std::string_view>{}(bytes);
    return text.str();
  });
  if (const int other = firstRankDiffering(fingerprint); other >= 0) {
    throw EveryRankError("mpirun: rank " + std::to_string(other) + " reads another volume from " +
                             spec +
                             " than rank 0 (its size, type, spacing or first slice differ): "
                             "every rank must read the same file",
                         2);
  }

  GLint maxSide = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
  BrickLayout chosen =
      BrickLayout::choose(dims, layoutTexelBytes(first.type()), maxTextureBytes, maxSide);
  // An axis of at most 2·kOverlap voxels is one brick of its own size in `chosen`, a storage
  // withStorage cannot cut: the smallest cuttable storage holds it as one brick as well.
  glm::ivec3 storage = glm::max(chosen.bricks()[0].size, glm::ivec3(BrickLayout::kMinStorage));
  BrickLayout layout = BrickLayout::withStorage(dims, storage);
  // At least one brick layer per rank: smaller bricks along z (kMinStorage at least). Ghost voxels
  // are held as whole brick layers (as many as cover the ghost width), so where a technique
  // reads them, four layers per rank keep the ghosts near a quarter of a slab on each side
  // (else two ranks would each hold the whole volume) at the cost of more slice pieces.
  const int wantedLayers = ranks * (ghostVoxels > 0 && ranks > 1 ? 4 : 1);
  while (layout.counts().z < wantedLayers && storage.z > BrickLayout::kMinStorage) {
    storage.z /= 2;
    layout = BrickLayout::withStorage(dims, storage);
  }
  const int layers = layout.counts().z;
  if (layers < ranks) {
    const auto counted = [](int n, const std::string& what) {
      return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    };
    throw EveryRankError(spec + ": " + counted(dims.z, "slice") +
                             (dims.z == 1 ? " makes " : " make ") + counted(layers, "brick layer") +
                             ", fewer than the " + std::to_string(ranks) +
                             " ranks; run fewer ranks",
                         2);
  }
  SlabRead read;
  SlabPart& part = read.part;
  part.dims = dims;
  part.layout = layout;
  part.ownedZ0 = me * layers / ranks;
  part.ownedZ1 = (me + 1) * layers / ranks;
  // Ghost layers: as many brick layers on each side as cover ghostVoxels voxels beyond the
  // owned samples (their textures carry the filter's apron themselves).
  part.heldZ0 = part.ownedZ0;
  part.heldZ1 = part.ownedZ1;
  const double ownedLow = part.ownedLowZ();
  const double ownedHigh = part.ownedHighZ();
  while (ghostVoxels > 0 && part.heldZ0 > 0 &&
         brickOfLayer(layout, part.heldZ0).low.z > ownedLow - ghostVoxels) {
    --part.heldZ0;
  }
  while (ghostVoxels > 0 && part.heldZ1 < layers &&
         brickOfLayer(layout, part.heldZ1 - 1).high.z < ownedHigh + ghostVoxels) {
    ++part.heldZ1;
  }
  part.voxelZ0 = brickOfLayer(layout, part.heldZ0).origin.z;
  const Brick& lastHeld = brickOfLayer(layout, part.heldZ1 - 1);
  const int voxelZ1 = std::min(lastHeld.origin.z + lastHeld.size.z, dims.z);
  for (int r = 0; r < ranks; ++r) {
    read.slabs.push_back(
        layersVoxels(layout, r * layers / ranks, (r + 1) * layers / ranks, dims.z));
  }

  LoadOptions slabLoad = load;
  slabLoad.region.crop = std::array<ReadRegion::Range, 3>{ReadRegion::Range{}, ReadRegion::Range{},
                                                          ReadRegion::Range{part.voxelZ0, voxelZ1}};
  read.volume = loadAlike(spec, slabLoad);

  // What every rank must agree on: the texture format, the value range, the derived defaults.
  int wide = textureFormatFor(read.volume) == GL_R32F ? 1 : 0;
  check(MPI_Allreduce(MPI_IN_PLACE, &wide, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  part.internalFormat = wide ? GL_R32F : GL_R16F;
  const ValueRange mine = valueRange(read.volume);
  float low = mine.min, high = mine.max;
  check(MPI_Allreduce(MPI_IN_PLACE, &low, 1, MPI_FLOAT, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
  check(MPI_Allreduce(MPI_IN_PLACE, &high, 1, MPI_FLOAT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  part.valueRange = {low, high};
  const std::array<int, 2> own = part.ownedVoxels();
  LevelCounts counts =
      levelCounts(read.volume, part.valueRange, own[0] - part.voxelZ0, own[1] - part.voxelZ0);
  check(MPI_Allreduce(MPI_IN_PLACE, counts.data(), int(counts.size()), MPI_UINT64_T, MPI_SUM,
                      MPI_COMM_WORLD),
        "MPI_Allreduce");
  part.derived = derivedDefaultsFromCounts(part.valueRange, counts);
  read.relay = std::make_unique<MpiRelay>();
  part.relay = read.relay.get();
  return read;
}

}  // namespace vsil::mpi
