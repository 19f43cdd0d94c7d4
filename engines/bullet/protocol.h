#pragma once
/// The private file format between the rockbench process and the single-precision helper
/// program (rockbench-bullet-float): a BulletInput one way, an EngineResult back. Binary,
/// native byte order, every double bit-exact (both programs come from the same build), with a
/// magic string and version so a stale helper is refused with a clear message.
#include <filesystem>
#include <string>

#include "engine/engine.h"
#include "engines/bullet/bullet_settings.h"

namespace rockbench::bullet {

/// Serializes an input to bytes / parses it back. Parse throws std::runtime_error on a bad
/// magic, version or truncated data.
std::string SerializeInput(const BulletInput& input);
BulletInput ParseInput(const std::string& bytes);

std::string SerializeOutput(const EngineResult& output);
EngineResult ParseOutput(const std::string& bytes);

/// Whole-file helpers (throw std::runtime_error naming the file).
std::string ReadBinaryFile(const std::filesystem::path& path);
void WriteBinaryFile(const std::filesystem::path& path, const std::string& bytes);

}  // namespace rockbench::bullet
