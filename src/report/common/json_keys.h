#pragma once
/// Reading a run folder's JSON files (summary.json, comparison.json) by dotted key ("a.b.c"),
/// with errors that name the file and the key. Absent keys and nulls are "no value"; a value of
/// the wrong type is an error.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace rockbench::report {

/// The file's JSON; throws std::runtime_error naming the file when it is not valid JSON.
nlohmann::json ReadJson(const std::filesystem::path& path);

/// The value at a dotted key, or nullptr when any part is missing.
const nlohmann::json* Find(const nlohmann::json& root, const std::string& dotted);

/// A number at a dotted key; NaN when absent or null. Throws std::runtime_error naming `file`
/// and the key when the value is not a number.
double OptNumber(const nlohmann::json& root, const std::string& key,
                 const std::filesystem::path& file);

/// As OptNumber, but an absent or null value is an error too.
double NeedNumber(const nlohmann::json& root, const std::string& key,
                  const std::filesystem::path& file);

/// A string at a dotted key; "" when absent or null; an error when of another type.
std::string OptString(const nlohmann::json& root, const std::string& key,
                      const std::filesystem::path& file);

/// A boolean at a dotted key; false when absent or null; an error when of another type.
bool OptBool(const nlohmann::json& root, const std::string& key, const std::filesystem::path& file);

}  // namespace rockbench::report
