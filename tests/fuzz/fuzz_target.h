#pragma once
/// What every fuzz target shares (docs/fuzzing.md). A target is one function,
/// LLVMFuzzerTestOneInput, built twice: with libFuzzer (scripts/fuzz.sh, clang) and with
/// replay_main.cc (the normal build, ctest), which runs it once on every file of its corpus and
/// regression folders.
///
/// The contract a target checks: bad input is a rockbench::SceneError (a message for the user);
/// anything else that escapes (another exception, a crash, a sanitizer report, a NaN result
/// reported as a success) is a finding. A finding aborts, so that libFuzzer keeps the input and
/// the replay test fails naming it.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "scene/scene.h"

#ifndef ROCKBENCH_SOURCE_DIR
#error "ROCKBENCH_SOURCE_DIR must name the repository root (tests/fuzz/CMakeLists.txt sets it)"
#endif

namespace rockbench::fuzz {

/// The repository root: shipped scenes and records are read from there, and fuzzed scene and
/// study texts are given a path in scenes/ so that their relative record paths resolve as the
/// shipped files' do.
inline std::filesystem::path SourceDir() {
  return ROCKBENCH_SOURCE_DIR;
}

/// The input as text (bytes as given: NUL, invalid UTF-8 and CR stay).
inline std::string Text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Prints what was found and aborts (libFuzzer saves the input as crash-<sha1>).
[[noreturn]] inline void Finding(std::string_view what) {
  std::fprintf(stderr, "\nrockbench fuzz FINDING: %.*s\n", static_cast<int>(what.size()),
               what.data());
  std::fflush(stderr);
  std::abort();
}

/// Runs `body`; a SceneError is the expected answer to bad input, any other exception is a
/// finding (named with its message, cut to 2000 characters).
template <typename Body>
void ExpectOnlySceneErrors(std::string_view target, Body&& body) {
  try {
    body();
  } catch (const SceneError&) {
    // Bad input, reported to the user: the contract holds.
  } catch (const std::exception& e) {
    std::string what = std::string(e.what()).substr(0, 2000);
    Finding(std::string(target) + ": an exception other than SceneError escaped: " + what);
  } catch (...) {
    Finding(std::string(target) + ": a non-standard exception escaped");
  }
}

}  // namespace rockbench::fuzz
