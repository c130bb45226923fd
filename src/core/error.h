#pragma once
// Errors. Library code throws; only main() turns an error into an exit status:
// InputError (bad files, flags, parameters: the user can fix it) exits 2, PartialFailure 3,
// everything else 1 (UnavailableError and CheckFailed without the words "internal error").
#include <stdexcept>
#include <string>

namespace vsil {

// `text` with each control byte (a NUL, ESC, CR, a newline: what a hostile file may put in a
// name or value that a message quotes) replaced by '?', so that it prints as one line, whole
// (a NUL would cut what() short) and without driving the terminal. Other bytes stay: a file's
// name that is not UTF-8 is named as it is (Python gives it back through os.fsdecode).
inline std::string oneLine(std::string text) {
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return text;
}

// oneLine's text with each byte of no valid UTF-8 sequence replaced by '?' too, for what a
// message quotes from a file's contents (binary bytes where a number should be: a terminal shows
// them as garbage, a JSON writer refuses them). UTF-8 stays (Schädel, →).
inline std::string printableText(std::string text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char lead = byte(i);
    // The length of a sequence starting here (RFC 3629: no overlong forms, nothing past U+10FFFF,
    // no surrogates), 0 when it starts none.
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xbf;  // the second byte's range
    if (lead < 0x80) {
      length = 1;
    } else if (lead >= 0xc2 && lead <= 0xdf) {
      length = 2;
    } else if (lead >= 0xe0 && lead <= 0xef) {
      length = 3;
      if (lead == 0xe0) low = 0xa0;
      if (lead == 0xed) high = 0x9f;
    } else if (lead >= 0xf0 && lead <= 0xf4) {
      length = 4;
      if (lead == 0xf0) low = 0x90;
      if (lead == 0xf4) high = 0x8f;
    }
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      const unsigned char next = byte(i + k);
      valid = k == 1 ? next >= low && next <= high : next >= 0x80 && next <= 0xbf;
    }
    if (!valid || lead < 0x20 || lead == 0x7f) {
      text[i++] = '?';
    } else {
      i += length;
    }
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
