#pragma once
// Output files are written whole or not at all: the bytes go to a temporary file in the target's
// directory, which is renamed over the target only once complete. A link is followed (the file it
// names is replaced, the link stays); a target that is neither a file nor a folder (/dev/null,
// /dev/stdout on a pipe, a FIFO) gets the complete bytes written into it, never a rename.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/unique_fd.h"

namespace vsil {

// The files one command reads, so that none of its outputs replaces one: `vsil render a.nrrd
// --out a.nrrd` replaced the volume with its picture (the input was read whole, then the output
// renamed over it), as did an output naming a header's detached data file, or measure-width's
// --json naming its image. The CLI turns the record on for its one command (main.cpp; a Python
// session reads and writes at will); the readers note each regular file they open; every output
// (AtomicOutputFile, OutputBatch::claim) that is one of them, links followed or a hard link, is
// refused with InputError before anything is written.
void recordInputFiles();
void noteInputFile(const std::filesystem::path& path);

// An output that a writer of its own makes (a video encoder that opens files by name), written
// whole or not at all like writeFileAtomically's: a hidden temporary ".NAME.XXXXXX.EXT" beside
// the target (it keeps the extension, which some writers choose their format by), registered
// for removal on the cleanup signals (installOutputCleanupOnSignals), renamed over the target by
// commit(), and removed when the object leaves scope uncommitted (an error, an early return).
//
//   AtomicOutputFile file("movie.avi");
//   encoder.open(file.temporaryPath()); ...; encoder.close();
//   file.commit();
class AtomicOutputFile {
 public:
  // Creates the temporary (empty). Throws InputError naming the target when its folder is
  // missing or not writable, or when it is a file the command read (noteInputFile).
  explicit AtomicOutputFile(const std::filesystem::path& target);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }
  // The temporary's descriptor, open for writing until commit() (for writers that take one).
  int descriptor() const { return fd_.get(); }
  // Whether commit() writes into the target (not a file or folder: /dev/null, a FIFO) instead
  // of renaming over it.
  bool intoSpecialFile() const { return intoSpecialFile_; }
  // Closes the descriptor and renames the temporary over the target (mode 0644), or for a
  // target that is not a file copies it in. Throws InputError naming the target when that
  // fails; the temporary is then removed.
  void commit();
  // commit()'s first half: closes the descriptor (a full disk can fail here), leaving the
  // complete temporary to rename. Throws InputError naming the target; commit() renames.
  void finish();

 private:
  void copyTemporaryIntoTarget();

  struct Registration;
  std::filesystem::path target_;       // as the caller named it, for messages
  std::filesystem::path destination_;  // what the rename replaces: the target, links followed
  std::filesystem::path temporary_;
  UniqueFd fd_;
  bool intoSpecialFile_ = false;
  bool committed_ = false;
  std::unique_ptr<Registration> registration_;
};

// The outputs of one run (render's --out, --state-out, --depth-out, --meta-out), all or none:
// each is written whole to its temporary first and only when every one is complete (written,
// closed) are they renamed over their targets, so a full disk or an unwritable folder for one
// leaves every target as it was. The writes into targets that are not files (/dev/full) go
// before the renames, so one failing leaves the files as they were. (The renames themselves, in
// one folder each, are the only steps that could fail between two outputs.)
//
//   OutputBatch outputs;
//   outputs.claim("--out", out); outputs.claim("--meta-out", meta);   // before any work
//   ...
//   outputs.add(out, pngBytes); outputs.add(meta, json);
//   outputs.commit();
enum class OutputKind { File, Folder };

class OutputBatch {
 public:
  // Refuses (InputError) an output naming the same file as one claimed before, or as a file the
  // command read so far (noteInputFile): the same path spelled otherwise (./o.png, dir/../o.png),
  // or a symlink or hard link to it; and a File output that names a folder (an existing one, or a
  // path ending in '/'). Empty paths (an output not asked for) are ignored.
  void claim(const std::string& flag, const std::filesystem::path& path,
             OutputKind kind = OutputKind::File);
  // Writes `bytes` to a temporary for `path` (not yet the target).
  void add(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
  void add(const std::filesystem::path& path, std::string_view text);
  // Renames every temporary over its target. Without commit() none is renamed.
  void commit();

 private:
  struct Claim {
    std::string flag;
    std::filesystem::path path, resolved;
  };
  std::vector<Claim> claims_;
  std::vector<std::unique_ptr<AtomicOutputFile>> files_;
};

// Throws InputError "<output>: folder F does not exist" (or "F is not a folder", or "cannot be
// examined: ...") unless the folder an output file goes into is there: checked before any work,
// since a missing one was otherwise found only when the result was written, after the render.
void refuseMissingFolder(const std::string& output, const std::filesystem::path& target);

// The folder a path names, written plainly: "out/", "out/." and "out" are out.
std::filesystem::path folderNamed(const std::filesystem::path& path);

// The same for an output folder that a command creates when missing (animate's and sweep's
// --out-dir): it is a folder, or its parent is there ("out/" names the folder out). Throws
// InputError "<output>: is not a folder" or as refuseMissingFolder for its parent.
void refuseOutputFolder(const std::string& output, std::filesystem::path folder);

// Throws InputError (naming the path) when the directory is missing or not writable.
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

// Whether `path` names this process's standard output (/dev/stdout, or the file or pipe it is),
// where a command should not also print the path it wrote.
bool namesStandardOutput(const std::filesystem::path& path);

// Installs handlers for SIGINT, SIGTERM, SIGHUP, SIGQUIT and SIGPIPE (those not ignored) that
// unlink the temporary file of any write in progress and then let the signal end the process as
// usual. Together with the rename, an interrupted run leaves neither a partial target nor a stray
// temporary; a target that existed before stays untouched. (SIGKILL cannot be caught: it may
// leave the hidden temporary ".NAME.XXXXXX.EXT", never a partial target.) Call once, from main().
void installOutputCleanupOnSignals();

}  // namespace vsil
