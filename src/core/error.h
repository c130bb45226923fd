#pragma once
// Errors. Library code throws; only main() turns an error into an exit status:
// InputError (bad files, flags, parameters: the user can fix it) exits 2, PartialFailure 3,
// everything else 1 (UnavailableError and CheckFailed without the words "internal error").
#include <stdexcept>
#include <string>

namespace vsil {

// `text` with each control byte (a NUL, ESC, CR, a newline: what a hostile file may put in a
// name or value that a message quotes) replaced by '?', so that it prints as one line, whole
// (a NUL would cut what() short) and without driving the terminal.
inline std::string oneLine(std::string text) {
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return text;
}

// Something the user gave us is wrong. The message names the file or flag and the problem,
// on one line, e.g. "bonsai.vti: zlib block 3 is truncated".
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(oneLine(message)) {}
};

// This machine lacks something the work needs (an OpenGL back end, a driver feature). The message
// names what is missing and what to try instead, on one line, e.g. "--gl egl: no EGL device or
// surfaceless platform (libEGL.so.1 not found); try --gl osmesa". Exits 1, printed as it is.
class UnavailableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A result failed the check the command runs on it (`vsil bench`'s self-checks: a row marked
// FAILED). Its numbers are not to be trusted, whether vsil or the input is at fault (a dataset
// file that is not the classic one). Exits 1, printed as it is, after every result is written.
class CheckFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The command did its work and wrote its results, but some parts of it failed, each reported
// where its result is (`vsil sweep`: a task's row holds its error). Exits 3; under MPI every rank
// ends in order (MPI_Finalize, not MPI_Abort), since the results were gathered. The message is
// one line, e.g. "1 of 100 tasks failed (their rows in sweep.json say why)".
class PartialFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Shorthand for the common "<where>: <what>" form.
[[noreturn]] inline void throwInputError(const std::string& where, const std::string& what) {
  throw InputError(where + ": " + what);
}

}  // namespace vsil
