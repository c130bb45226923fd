#include "core/atomic_file.h"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>

#include "core/error.h"

namespace vsil {
namespace {

// The temporaries being written, for the signal handler: fixed slots, claimed and released with
// lock-free atomics (async-signal-safe), paths copied in before a slot is marked in use.
constexpr int kSlots = 16;
enum SlotState : int { Free, Claimed, InUse };
std::atomic<int> slotState[kSlots];
char slotPath[kSlots][PATH_MAX];
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

void cleanupOnSignal(int signal) {
  for (int i = 0; i < kSlots; ++i) {
    if (slotState[i].load() == InUse) ::unlink(slotPath[i]);
  }
  // SA_RESETHAND restored the default action; the signal is delivered once we return.
  ::raise(signal);
}

// Blocks the cleanup signals for its lifetime, so that a temporary is never created without
// being registered.
class SignalBlock {
 public:
  SignalBlock() {
    sigset_t set;
    sigemptyset(&set);
    for (int signal : kCleanupSignals) sigaddset(&set, signal);
    pthread_sigmask(SIG_BLOCK, &set, &previous_);
  }
  ~SignalBlock() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t previous_;
};

// The registration of one temporary; unregisters when it leaves scope. Without a free slot
// (more than kSlots writes at once) the file is written unregistered.
class TempRegistration {
 public:
  explicit TempRegistration(const std::string& path) {
    if (path.size() >= PATH_MAX) return;
    for (int i = 0; i < kSlots; ++i) {
      int expected = Free;
      if (slotState[i].compare_exchange_strong(expected, Claimed)) {
        std::memcpy(slotPath[i], path.c_str(), path.size() + 1);
        slotState[i].store(InUse);
        slot_ = i;
        return;
      }
    }
  }
  ~TempRegistration() {
    if (slot_ >= 0) slotState[slot_].store(Free);
  }
  TempRegistration(const TempRegistration&) = delete;
  TempRegistration& operator=(const TempRegistration&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace

void installOutputCleanupOnSignals() {
  for (int signal : kCleanupSignals) {
    struct sigaction previous {};
    if (sigaction(signal, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = cleanupOnSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(signal, &action, nullptr);
  }
}

void writeFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  const std::string target = path.string();
  if (target.empty()) throw InputError("output path is empty");
  std::filesystem::path dir = path.parent_path();
  if (dir.empty()) dir = ".";
  // A hidden temporary beside the target: same file system, so rename() is atomic.
  std::string temp = (dir / ("." + path.filename().string() + ".XXXXXX")).string();
  int fd = -1;
  std::optional<TempRegistration> registration;
  {
    const SignalBlock block;
    fd = mkstemp(temp.data());
    if (fd >= 0) registration.emplace(temp);
  }
  if (fd < 0)
    throwInputError(target, std::string("cannot create the output file: ") + std::strerror(errno));
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      ::unlink(temp.c_str());
      throwInputError(target, std::string("cannot write: ") + std::strerror(err));
    }
    written += std::size_t(n);
  }
  fchmod(fd, 0644);
  if (::close(fd) != 0 || std::rename(temp.c_str(), target.c_str()) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    throwInputError(target, std::string("cannot write: ") + std::strerror(err));
  }
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view text) {
  writeFileAtomically(path, std::span<const std::uint8_t>(
                                reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace vsil
