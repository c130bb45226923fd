#pragma once
// `mpirun -np N vsil render` (issue 35): each rank reads only its slab of the volume (a run of
// the whole volume's brick layers along z, slicing/slab.h), renders the samples it owns, and the
// ranks combine their partial frames by the technique's rule (core/composition.h). Built only
// with VSIL_HAVE_MPI.
#include <memory>
#include <string>

#include "io/volume_loader.h"
#include "slicing/slab.h"

namespace vsil::mpi {

struct SlabRead {
  Volume volume;  // the whole volume's z from part.voxelZ0 on
  SlabPart part;
  std::unique_ptr<SlabRelay> relay;  // part.relay points here
  // For the metadata: every rank's owned voxels [z0, z1) along z.
  std::vector<std::array<int, 2>> slabs;
};

// Reads this rank's slab of `spec` (--crop z0:z1 through the readers: NRRD and raw seek to it,
// compressed and generated volumes are made whole and cut), after a one-slice read for the
// file's dimensions. The value range, the derived defaults and the texture format are agreed
// with the other ranks. Throws InputError for --crop or --stride (not combined yet) and when
// the volume has fewer brick layers along z than there are ranks.
// `ghostVoxels` (slab.h techniqueGhostVoxels): the rank also holds as many brick layers on each
// side as cover that many voxels beyond its own (ghost layers, drawn where the technique reads
// neighbouring pixels of a slice, never owned).
SlabRead readSlab(const std::string& spec, LoadOptions load, std::uint64_t maxTextureBytes,
                  int ghostVoxels);

// The file's header and its first slice (what readSlab reads first): the dimensions
// (fileDims) and spacing for the frame's view before the slabs are chosen. Throws
// EveryRankError for --crop or --stride, and on every rank, with the lowest failing rank's
// message said once, for a file any rank cannot read (as readSlab for its slab's part).
Volume probeSlab(const std::string& spec, LoadOptions load);
glm::ivec3 fileDims(const Volume& probe);

// Gathers a double from every rank on rank 0 (empty elsewhere).
std::vector<double> gatherOnRoot(double value);

}  // namespace vsil::mpi
