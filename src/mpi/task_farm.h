#pragma once
// Independent tasks spread over the ranks of the MPI world, one at a time as ranks become free
// (dynamic scheduling: uneven tasks balance), with every result gathered on rank 0. Without MPI,
// or in a world of one rank, the calling process runs every task itself, in order.
//
// Rank 0 hands out tasks and, between answering the others, runs tasks itself: no rank only
// waits. A rank asking for work while rank 0 runs a task waits at most that task's time.
// Waiting ranks sleep between polls (no busy waiting), so that mpirun --oversubscribe with more
// ranks than cores leaves the cores to the ranks that work.
#include <functional>
#include <string>

namespace vsil::mpi {

// Runs task `task` on the calling rank and returns its result as text (what rank 0 receives).
// It should not throw: a task that fails says so in its result. An exception ends the rank
// (and, through mpi::finish, the world).
using RunTask = std::function<std::string(int task)>;
// Called on rank 0 only, once per task, in the order results arrive: the task, its result, the
// rank that ran it.
using TakeResult = std::function<void(int task, const std::string& result, int rank)>;

// Every rank of the world calls this with the same `taskCount`; it returns on each when all
// tasks are done and, on rank 0, taken.
void runTaskFarm(int taskCount, const RunTask& run, const TakeResult& take);

namespace detail {
// The farm over several ranks (task_farm_mpi.cpp, built with MPI only).
void farmOverRanks(int taskCount, const RunTask& run, const TakeResult& take);
}  // namespace detail

}  // namespace vsil::mpi
