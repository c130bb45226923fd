// The task farm over MPI ranks (task_farm.h). Messages on MPI_COMM_WORLD:
//   a worker -> rank 0, tag kResultTag: "TASK\nRESULT" for a finished task, "-1\n" when it
//     starts (ready for its first task);
//   rank 0 -> a worker, tag kTaskTag: one int, the next task, or -1: no more, stop.
// Every message from a worker is answered by exactly one from rank 0, so each worker gets one
// stop and the farm ends when every task is taken and every worker is stopped.
#include <mpi.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "mpi/mpi_world.h"
#include "mpi/task_farm.h"

namespace vsil::mpi::detail {
namespace {

constexpr int kResultTag = 3501;
constexpr int kTaskTag = 3502;
// How long a waiting rank sleeps between polls: short against any render, long enough that a
// waiting rank costs no core (Open MPI's blocking calls spin).
constexpr auto kPollInterval = std::chrono::microseconds(200);

void check(int code, const char* call) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string("task farm: ") + call +
                           " failed: " + std::string(text, std::size_t(length)));
}

void waitGently(MPI_Request& request, const char* what) {
  for (;;) {
    int done = 0;
    check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), what);
    if (done) return;
    std::this_thread::sleep_for(kPollInterval);
  }
}

void sendResult(int task, const std::string& result) {
  const std::string message = std::to_string(task) + "\n" + result;
  MPI_Request request;
  check(MPI_Isend(message.data(), int(message.size()), MPI_CHAR, 0, kResultTag, MPI_COMM_WORLD,
                  &request),
        "MPI_Isend");
  waitGently(request, "MPI_Isend");
}

int receiveTask() {
  int task = -1;
  MPI_Request request;
  check(MPI_Irecv(&task, 1, MPI_INT, 0, kTaskTag, MPI_COMM_WORLD, &request), "MPI_Irecv");
  waitGently(request, "MPI_Irecv");
  return task;
}

void work(const RunTask& run) {
  sendResult(-1, "");
  for (int task = receiveTask(); task >= 0; task = receiveTask()) sendResult(task, run(task));
}

// A finished task or a worker's first call, if one waits: its task (-1: none), result, rank.
struct Message {
  int task = -1;
  std::string result;
  int rank = -1;
};
bool receiveIfWaiting(Message& message) {
  int waiting = 0;
  MPI_Status status;
  check(MPI_Iprobe(MPI_ANY_SOURCE, kResultTag, MPI_COMM_WORLD, &waiting, &status), "MPI_Iprobe");
  if (!waiting) return false;
  int length = 0;
  check(MPI_Get_count(&status, MPI_CHAR, &length), "MPI_Get_count");
  std::vector<char> bytes(std::size_t(length) + 1);
  check(MPI_Recv(bytes.data(), length, MPI_CHAR, status.MPI_SOURCE, kResultTag, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE),
        "MPI_Recv");
  const std::string text(bytes.data(), std::size_t(length));
  const std::size_t newline = text.find('\n');
  if (newline == std::string::npos) throw std::runtime_error("task farm: a malformed message");
  message.task = std::stoi(text.substr(0, newline));
  message.result = text.substr(newline + 1);
  message.rank = status.MPI_SOURCE;
  return true;
}

void lead(int taskCount, const RunTask& run, const TakeResult& take) {
  const int workers = size() - 1;
  int next = 0, taken = 0, stopped = 0;
  Message message;
  while (taken < taskCount || stopped < workers) {
    if (receiveIfWaiting(message)) {
      if (message.task >= 0) {
        take(message.task, message.result, message.rank);
        ++taken;
      }
      const int task = next < taskCount ? next++ : -1;
      if (task < 0) ++stopped;
      check(MPI_Send(&task, 1, MPI_INT, message.rank, kTaskTag, MPI_COMM_WORLD), "MPI_Send");
      continue;  // answer every waiting rank before working
    }
    if (next < taskCount) {
      const int task = next++;
      take(task, run(task), 0);
      ++taken;
      continue;
    }
    std::this_thread::sleep_for(kPollInterval);
  }
}

}  // namespace

void farmOverRanks(int taskCount, const RunTask& run, const TakeResult& take) {
  if (rank() == 0) {
    lead(taskCount, run, take);
  } else {
    work(run);
  }
}

}  // namespace vsil::mpi::detail
