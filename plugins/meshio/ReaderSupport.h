#pragma once
/// What every mesh reader shares: located errors, message formatting and file access. Private to
/// the readers (fascia::meshio::detail); the public entry points are in MeshReaders.h.
#include "fascia/base/Format.h"

#include <string>
#include <string_view>
#include <vector>

namespace fascia::meshio::detail {

/// The formats readMesh knows, for "unknown extension" messages.
extern const char* const kSupportedFormats;

/// Throws an input error located at file:line (line 0: the file as a whole).
[[noreturn]] void fail(const std::string& file, int line, const std::string& message,
                       std::vector<std::string> notes = {});

/// Throws an input error located at byte offset `byte` of a binary file ("file: byte N: error: ...").
[[noreturn]] void failAtByte(const std::string& file, long long byte, const std::string& message,
                             std::vector<std::string> notes = {});

/// 's' in single quotes, cut after 60 characters so that a run of garbage stays readable.
std::string quoted(std::string_view s);
/// The extension of path, lower case, with its dot (".msh"); empty when there is none.
std::string lowerExtension(const std::string& path);
/// "1 node", "3 nodes".
std::string plural(long long n, const std::string& word);
/// Numbers in the readers' messages: formatNumber(v, 6), 6 significant digits.
using core::formatNumber;

/// Fails unless path names a regular file we can open.
void checkReadable(const std::string& path);
/// A reservation for a count read from a file: a hint, capped so that a corrupt header announcing
/// billions of records cannot exhaust memory before the records themselves are found missing.
size_t reserveHint(long long n);
/// The whole file (checked with checkReadable), without a UTF-8 byte-order mark unless keepBom
/// (a reader that reports byte offsets keeps the file's bytes as they are).
std::string readWholeFile(const std::string& path, bool keepBom = false);

} // namespace fascia::meshio::detail
