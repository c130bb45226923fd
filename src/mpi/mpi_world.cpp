#include "mpi/mpi_world.h"

#include <cstdlib>
#include <limits>
#include <string>

#include "core/error.h"

#ifdef VSIL_HAVE_MPI
#include <mpi.h>
#endif

namespace vsil::mpi {

namespace {
bool failingAlike = false;

bool hasEnv(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0';
}
}  // namespace

bool built() {
#ifdef VSIL_HAVE_MPI
  return true;
#else
  return false;
#endif
}

bool launched() {
  if (const char* forced = std::getenv("VSIL_MPI"); forced != nullptr && *forced != '\0')
    return std::string(forced) == "1";
  return hasEnv("OMPI_COMM_WORLD_SIZE") || hasEnv("PMIX_RANK") || hasEnv("PMI_RANK");
}

#ifdef VSIL_HAVE_MPI

bool active() {
  int initialized = 0;
  int finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}

void initIfLaunched(int* argc, char*** argv) {
  if (!launched() || active()) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  // Errors come back as codes, so that they become vsil errors naming what failed.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

int rank() {
  if (!active()) return 0;
  int value = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &value);
  return value;
}

int size() {
  if (!active()) return 1;
  int value = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &value);
  return value;
}

namespace {

// The lowest rank where `holds`, or -1 where it holds on none: a collective.
int lowestRankWhere(bool holds) {
  const int mine = holds ? rank() : std::numeric_limits<int>::max();
  int lowest = mine;
  MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return lowest == std::numeric_limits<int>::max() ? -1 : lowest;
}

// `root`'s `text` on every rank: a collective. What the callers send (a command line, a
// volume's fingerprint, a one-line message) is far below INT_MAX bytes.
std::string broadcastText(std::string text, int root) {
  unsigned long long length = text.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD);
  text.resize(std::size_t(length));
  if (length > 0) MPI_Bcast(text.data(), int(length), MPI_CHAR, root, MPI_COMM_WORLD);
  return text;
}

}  // namespace

int firstRankDiffering(const std::string& mine) {
  if (!active() || size() < 2) return -1;
  return lowestRankWhere(broadcastText(rank() == 0 ? mine : std::string(), 0) != mine);
}

void refuseAlike(const std::optional<std::string>& refusal) {
  if (!active() || size() < 2) {
    if (refusal) throw InputError(*refusal);
    return;
  }
  const int lowest = lowestRankWhere(refusal.has_value());
  if (lowest < 0) return;
  throw EveryRankError(broadcastText(rank() == lowest ? *refusal : std::string(), lowest), 2);
}

void requireSameCommand(int argc, char** argv) {
  std::string arguments;  // each argument ended by a NUL: "a b" and "a" "b" differ
  for (int i = 1; i < argc; ++i) arguments.append(argv[i]).push_back('\0');
  if (const int lowest = firstRankDiffering(arguments); lowest >= 0) {
    throw EveryRankError("mpirun: rank " + std::to_string(lowest) +
                             " runs another command line than rank 0: every rank must run the "
                             "same vsil command",
                         2);
  }
}

int finish(int exitCode) {
  if (!active()) return exitCode;
  if (exitCode != 0 && size() > 1 && !failingAlike) MPI_Abort(MPI_COMM_WORLD, exitCode);
  MPI_Finalize();
  return exitCode;
}

#else

bool active() {
  return false;
}
void initIfLaunched(int*, char***) {}
void requireSameCommand(int, char**) {}
int firstRankDiffering(const std::string&) {
  return -1;
}
void refuseAlike(const std::optional<std::string>& refusal) {
  if (refusal) throw InputError(*refusal);
}
int rank() {
  return 0;
}
int size() {
  return 1;
}
int finish(int exitCode) {
  return exitCode;
}

#endif

void failAlike() {
  failingAlike = true;
}

void require(const std::string& what) {
  if (!built())
    throw UnavailableError(what +
                           " needs MPI: this vsil was built without it (install "
                           "libopenmpi-dev and openmpi-bin, then configure again)");
  if (!active())
    throw UnavailableError(what +
                           " needs an MPI launcher: run it as mpirun -np N vsil ... "
                           "(or srun under Slurm)");
}

std::string errorPrefix() {
  if (size() <= 1) return "vsil: ";
  return "vsil (rank " + std::to_string(rank()) + "): ";
}

}  // namespace vsil::mpi
