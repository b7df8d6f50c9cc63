#pragma once
// Files that are either absent, the old version, or the complete new version: written to a
// temporary name of its own in the same folder (NAME.tmp.XXXXXX, so that processes writing the
// same file at once do not share it: the last rename wins), flushed to disk (fsync), then
// renamed over the target, and the folder entry flushed too. Not collective: call on the one
// rank that writes.
#include <filesystem>
#include <string_view>

namespace suite::io {

void write_file_atomic(const std::filesystem::path& path, std::string_view content);

// fsync of an existing file or folder; throws LibraryError naming the path on failure.
void fsync_path(const std::filesystem::path& path);

}  // namespace suite::io
