#pragma once
/// Whole files in and out: read as stored, written atomically (a temporary name renamed only when
/// complete, so that no reader ever sees half a file).
#include <filesystem>
#include <string>

namespace rockbench {

/// The whole content of a file (bytes as stored). Throws std::runtime_error naming the file
/// when it cannot be opened or read.
std::string ReadTextFile(const std::filesystem::path& path);

/// Writes `text` to `path` atomically: to "<path>.tmp.<pid>" in the same folder, fsync, then
/// rename over `path`. Creates missing parent folders. Throws std::runtime_error.
void WriteFileAtomic(const std::filesystem::path& path, const std::string& text);

}  // namespace rockbench
