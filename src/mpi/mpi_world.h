#pragma once
// The MPI world vsil runs in (Open MPI from Debian, optional at build time). vsil initializes
// MPI only when an MPI launcher (mpirun, srun) started the process: a plain `vsil render` pays
// nothing for MPI, and a build without MPI renders as before. Code that needs MPI includes
// <mpi.h> itself, in files built only with VSIL_HAVE_MPI (src/mpi/CMakeLists.txt).
#include <optional>
#include <string>

#include "core/error.h"

namespace vsil::mpi {

// An error every rank meets alike (a refusal decided from the flags alone, before reading):
// main() prints it on rank 0 only, so that N ranks do not print N copies.
// `status` is the exit status (1: unavailable, as UnavailableError; 2: the command's own fault).
class EveryRankError : public UnavailableError {
 public:
  explicit EveryRankError(const std::string& message, int status = 1)
      : UnavailableError(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// Whether this build has MPI.
bool built();
// Whether an MPI launcher started this process: Open MPI's mpirun (OMPI_COMM_WORLD_SIZE),
// a PMIx or PMI launcher such as Slurm's srun (PMIX_RANK, PMI_RANK), or VSIL_MPI=1.
bool launched();
// First thing in main(): MPI_Init_thread (MPI_THREAD_FUNNELED: only the main thread calls MPI)
// when launched() and built(); nothing otherwise.
void initIfLaunched(int* argc, char*** argv);
// Every rank must run the same command: ranks that differ (`mpirun -n 1 vsil render a : -n 1 vsil
// info b`, another volume or view on one rank) would wait for each other forever or gather
// unlike pictures into one. Compares each rank's arguments (argv[1..]) with rank 0's, a
// collective every rank of an active world calls first; throws EveryRankError (status 2) on
// every rank when any differs. Nothing without MPI or with one rank.
void requireSameCommand(int argc, char** argv);
// The lowest rank whose `mine` differs from rank 0's, or -1 when every rank's is the same: a
// collective every rank calls. -1 without MPI or with one rank.
int firstRankDiffering(const std::string& mine);
// Checks that every rank runs alike but whose outcome may still differ between ranks (a file or
// folder on one node, its memory): `refusal` is this rank's error message, if it refused. A
// collective every rank calls: where any rank refused, every rank throws EveryRankError (status
// 2) with the lowest refusing rank's message, said once by rank 0, so that no rank goes on into
// a collective the others never reach. Without MPI or with one rank: InputError(*refusal).
void refuseAlike(const std::optional<std::string>& refusal);
// Whether MPI is initialized and not yet finalized.
bool active();
// This process's rank in MPI_COMM_WORLD and the world's size: 0 and 1 when MPI is not active.
int rank();
int size();
// The end of a process that initialized MPI: MPI_Finalize when `exitCode` is 0; otherwise, in
// a world of several ranks, MPI_Abort with it, so that no rank waits forever in a collective
// for one that failed. Returns exitCode.
int finish(int exitCode);
// Says that this process fails as every rank does (an EveryRankError): finish() then
// finalizes instead of aborting, so that no rank is killed before rank 0 has printed the error.
void failAlike();
// Throws UnavailableError "<what> needs MPI: this vsil was built without it (...)" in a build
// without MPI, and "<what> needs an MPI launcher (mpirun -np N vsil ...)" when not launched.
void require(const std::string& what);
// How an error line starts on this rank: "vsil: " on rank 0 and without MPI, "vsil (rank R): "
// on the others, so that a failure on one rank of many says which.
std::string errorPrefix();

}  // namespace vsil::mpi
