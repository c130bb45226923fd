#include "mpi/task_farm.h"

#include "mpi/mpi_world.h"

namespace vsil::mpi {

void runTaskFarm(int taskCount, const RunTask& run, const TakeResult& take) {
#ifdef VSIL_HAVE_MPI
  if (active() && size() > 1) {
    detail::farmOverRanks(taskCount, run, take);
    return;
  }
#endif
  for (int task = 0; task < taskCount; ++task) take(task, run(task), 0);
}

}  // namespace vsil::mpi
