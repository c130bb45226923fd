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
#include <mutex>
#include <string>
#include <utility>

#include "core/error.h"

namespace vsil {
namespace {

// The regular files the command read (recordInputFiles), by device and inode.
struct InputFiles {
  std::mutex mutex;
  bool recording = false;
  std::vector<std::pair<dev_t, ino_t>> ids;
  std::vector<std::string> names;  // as first opened, for messages
};
InputFiles& inputFiles() {
  static InputFiles files;
  return files;
}

// The input file that writing `target` (links followed) would replace, as it was named; "" for
// none.
std::string inputNamedBy(const std::filesystem::path& target) {
  InputFiles& inputs = inputFiles();
  const std::lock_guard lock(inputs.mutex);
  struct stat status;
  if (inputs.ids.empty() || ::stat(target.c_str(), &status) != 0) return "";
  for (std::size_t i = 0; i < inputs.ids.size(); ++i) {
    if (inputs.ids[i] == std::pair(status.st_dev, status.st_ino)) return inputs.names[i];
  }
  return "";
}

// A file output that names a folder ("out/", or an existing folder, through links) would be
// written and then fail its rename: refused before any work.
void refuseFolderTarget(const std::string& output, const std::filesystem::path& target) {
  std::error_code error;
  if (target.string().ends_with('/') || std::filesystem::is_directory(target, error)) {
    throw InputError(output + ": is a folder; give the output a file name");
  }
}

void refuseInputTarget(const std::string& output, const std::filesystem::path& target) {
  const std::string input = inputNamedBy(target);
  if (input.empty()) return;
  throw InputError(output + ": names " + (input == target.string() ? "" : input + ", ") +
                   "a file this command reads; give the output its own file");
}

// The temporaries being written, for the signal handler: fixed slots, claimed and released with
// lock-free atomics (async-signal-safe), paths copied in before a slot is marked in use.
constexpr int kSlots = 16;
enum SlotState : int { Free, Claimed, InUse };
std::atomic<int> slotState[kSlots];
char slotPath[kSlots][PATH_MAX];
// SIGPIPE: an output written into a pipe whose reader has gone (render --out /dev/stdout | true).
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};

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

// Writes all of `bytes` to `fd`; throws InputError naming `target` when that fails.
void writeAll(int fd, std::span<const std::uint8_t> bytes, const std::filesystem::path& target) {
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      throwInputError(target.string(), std::string("cannot write: ") + std::strerror(errno));
    }
    written += std::size_t(n);
  }
}

// What a write to `path` replaces: the path itself, or the end of its chain of links (as open()
// follows them; a link to nothing names the file it would create). Throws InputError naming
// `path` for a chain that does not end (a loop), where open() fails with ELOOP.
std::filesystem::path linkTarget(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  fs::path at = path;
  std::error_code error;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(at, error)); ++hops) {
    if (hops == 40)
      throwInputError(path.string(), "cannot write: " + std::string(std::strerror(ELOOP)));
    const fs::path next = fs::read_symlink(at, error);
    if (error) break;
    at = next.is_absolute() ? next : at.parent_path() / next;
  }
  return at;
}

}  // namespace

void refuseMissingFolder(const std::string& output, const std::filesystem::path& target) {
  const std::filesystem::path folder =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::error_code error;
  const std::filesystem::file_type type = std::filesystem::status(folder, error).type();
  if (type == std::filesystem::file_type::not_found) {
    throw InputError(output + ": folder " + folder.string() + " does not exist");
  }
  if (error) throw InputError(output + ": cannot be examined: " + error.message());
  if (type != std::filesystem::file_type::directory) {
    throw InputError(output + ": " + folder.string() + " is not a folder");
  }
}

std::filesystem::path folderNamed(const std::filesystem::path& path) {
  const std::filesystem::path folder = path.lexically_normal();  // out/. is out/
  return folder.has_filename() || !folder.has_parent_path() ? folder : folder.parent_path();
}

void refuseOutputFolder(const std::string& output, std::filesystem::path folder) {
  folder = folderNamed(folder);
  std::error_code error;
  const std::filesystem::file_type type = std::filesystem::status(folder, error).type();
  if (type == std::filesystem::file_type::not_found &&
      std::filesystem::is_symlink(std::filesystem::symlink_status(folder, error))) {
    throw InputError(output + ": is a link to nothing (" +
                     std::filesystem::read_symlink(folder, error).string() + ")");
  }
  if (type == std::filesystem::file_type::not_found) return refuseMissingFolder(output, folder);
  if (error) throw InputError(output + ": cannot be examined: " + error.message());
  if (type != std::filesystem::file_type::directory) throw InputError(output + ": is not a folder");
}

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

struct AtomicOutputFile::Registration {
  explicit Registration(const std::string& path) : slot(path) {}
  TempRegistration slot;
};

void recordInputFiles() {
  InputFiles& inputs = inputFiles();
  const std::lock_guard lock(inputs.mutex);
  inputs.recording = true;
}

void noteInputFile(const std::filesystem::path& path) {
  InputFiles& inputs = inputFiles();
  const std::lock_guard lock(inputs.mutex);
  struct stat status;
  if (!inputs.recording || ::stat(path.c_str(), &status) != 0 || !S_ISREG(status.st_mode)) return;
  const std::pair id(status.st_dev, status.st_ino);
  for (const auto& known : inputs.ids) {
    if (known == id) return;
  }
  inputs.ids.push_back(id);
  inputs.names.push_back(path.string());
}

AtomicOutputFile::AtomicOutputFile(const std::filesystem::path& target) : target_(target) {
  namespace fs = std::filesystem;
  if (target.empty()) throw InputError("output path is empty");
  refuseFolderTarget(target.string(), target);
  refuseInputTarget(target.string(), target);
  // A link is followed: the file it names is replaced and the link stays (a rename over the
  // link would replace the link itself).
  destination_ = linkTarget(target);
  std::error_code error;
  // A target that is neither a file nor a folder (/dev/null, /dev/stdout on a pipe or a
  // terminal, a FIFO) is written into at commit(), never renamed over: run as root, a rename
  // would put a file in the place of /dev/null. Its temporary goes to the temporary folder.
  struct stat status;
  intoSpecialFile_ =
      ::stat(target.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISDIR(status.st_mode);
  fs::path dir = destination_.parent_path();
  if (intoSpecialFile_) {
    dir = fs::temp_directory_path(error);
    if (error) dir = "/tmp";
  }
  if (dir.empty()) dir = ".";
  // A hidden temporary beside the target: same file system, so rename() is atomic.
  // The extension kept at the end (a writer may choose its format by it), when it is short
  // enough to be one: long names keep their room below the file system's limit.
  std::string extension = destination_.extension().string();
  if (extension.size() > 8) extension.clear();
  // The target's name, cut where the temporary's would pass the file system's limit on a name
  // (a legal target of 244 to 255 bytes could not be written): it only has to be unique.
  std::string name = destination_.filename().string();
  const std::size_t room = std::size_t(NAME_MAX) - std::string(".").size() -
                           std::string(".XXXXXX").size() - extension.size();
  if (name.size() > room) name.resize(room);
  std::string temp = (dir / ("." + name + ".XXXXXX" + extension)).string();
  {
    const SignalBlock block;
    fd_ = UniqueFd(mkstemps(temp.data(), int(extension.size())));
    if (fd_.valid()) registration_ = std::make_unique<Registration>(temp);
  }
  if (!fd_.valid()) {
    throwInputError(target.string(),
                    std::string("cannot create the output file: ") + std::strerror(errno));
  }
  temporary_ = temp;
}

AtomicOutputFile::~AtomicOutputFile() {
  fd_.close();
  if (!committed_) ::unlink(temporary_.c_str());
}

void AtomicOutputFile::finish() {
  if (!fd_.valid()) return;
  fchmod(fd_.get(), 0644);
  if (fd_.close() != 0) {
    const int err = errno;
    throwInputError(target_.string(), std::string("cannot write: ") + std::strerror(err));
  }
}

void AtomicOutputFile::commit() {
  finish();
  if (intoSpecialFile_) {
    copyTemporaryIntoTarget();
    ::unlink(temporary_.c_str());
  } else if (std::rename(temporary_.c_str(), destination_.c_str()) != 0) {
    const int err = errno;
    throwInputError(target_.string(), std::string("cannot write: ") + std::strerror(err));
  }
  committed_ = true;
}

void AtomicOutputFile::copyTemporaryIntoTarget() {
  const auto fail = [&](const char* what) {
    throwInputError(target_.string(), std::string(what) + std::strerror(errno));
  };
  const UniqueFd in(::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC));
  if (!in.valid()) fail("cannot read back the output: ");
  UniqueFd out(::open(target_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY));
  if (!out.valid()) fail("cannot write: ");
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(in.get(), buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail("cannot read back the output: ");
    if (got == 0) break;
    writeAll(out.get(), {reinterpret_cast<const std::uint8_t*>(buffer), std::size_t(got)}, target_);
  }
  if (out.close() != 0) fail("cannot write: ");
}

bool namesStandardOutput(const std::filesystem::path& path) {
  struct stat named, standardOutput;
  return ::stat(path.c_str(), &named) == 0 && ::fstat(STDOUT_FILENO, &standardOutput) == 0 &&
         named.st_dev == standardOutput.st_dev && named.st_ino == standardOutput.st_ino;
}

namespace {

std::unique_ptr<AtomicOutputFile> writeTemporary(const std::filesystem::path& path,
                                                 std::span<const std::uint8_t> bytes) {
  auto file = std::make_unique<AtomicOutputFile>(path);
  writeAll(file->descriptor(), bytes, path);
  file->finish();
  return file;
}

// The file a path names, for comparing outputs: the end of its links (a link to a file not yet
// there included), its folder's real path (symlinks, "..", "." resolved) joined with the name.
std::filesystem::path resolvedOutput(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path written = linkTarget(path);
  // Absolute first: weakly_canonical leaves a relative path whose first part does not exist
  // ("o.png") relative, while "./o.png" becomes absolute, and the two would compare unequal.
  const std::filesystem::path absolute = std::filesystem::absolute(written, ec);
  std::filesystem::path resolved = std::filesystem::weakly_canonical(absolute, ec);
  if (ec) resolved = absolute.lexically_normal();
  return resolved;
}

}  // namespace

void OutputBatch::claim(const std::string& flag, const std::filesystem::path& path,
                        OutputKind kind) {
  if (path.empty()) return;
  if (kind == OutputKind::File) {
    refuseFolderTarget(flag + " " + path.string(), path);
    refuseMissingFolder(flag + " " + path.string(), path);
  }
  refuseInputTarget(flag + " " + path.string(), path);
  Claim claim{flag, path, resolvedOutput(path)};
  for (const Claim& other : claims_) {
    std::error_code ec;
    const bool same = other.resolved == claim.resolved ||
                      std::filesystem::equivalent(other.path, claim.path, ec);  // hard links
    if (same) {
      throw InputError(flag + " " + path.string() + ": names the same file as " + other.flag + " " +
                       other.path.string() + "; give each output its own file");
    }
  }
  claims_.push_back(std::move(claim));
}

void OutputBatch::add(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  // An input read since the claims (a header's detached data file), named by the output's flag.
  for (const Claim& claim : claims_) {
    if (claim.path == path) refuseInputTarget(claim.flag + " " + path.string(), path);
  }
  files_.push_back(writeTemporary(path, bytes));
}

void OutputBatch::add(const std::filesystem::path& path, std::string_view text) {
  add(path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                          text.size()));
}

void OutputBatch::commit() {
  // Writes into special files first: they fail (a full device) more readily than renames, and
  // while they do no target has been replaced yet.
  for (const auto& file : files_) {
    if (file->intoSpecialFile()) file->commit();
  }
  for (const auto& file : files_) {
    if (!file->intoSpecialFile()) file->commit();
  }
}

void writeFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  writeTemporary(path, bytes)->commit();
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view text) {
  writeFileAtomically(path, std::span<const std::uint8_t>(
                                reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace vsil
