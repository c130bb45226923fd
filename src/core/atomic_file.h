#pragma once
// Output files are written whole or not at all: the bytes go to a temporary file in the target's
// directory, which is renamed over the target only once complete.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

namespace vsil {

// Throws InputError (naming the path) when the directory is missing or not writable.
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

// Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGQUIT (those not ignored) that unlink the
// temporary file of any write in progress and then let the signal end the process as usual.
// Together with the rename, an interrupted run leaves neither a partial target nor a stray
// temporary; a target that existed before stays untouched. (SIGKILL cannot be caught: it may
// leave the hidden temporary ".NAME.XXXXXX", never a partial target.) Call once, from main().
void installOutputCleanupOnSignals();

}  // namespace vsil
