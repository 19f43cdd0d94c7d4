#pragma once
/// Names a report reads back from a results folder (summary.json's and study.json's engine keys,
/// the engine columns of sweep.csv and members.csv) become file and folder names, figure titles
/// and page text. A folder someone shares is data: only names of the engine-name alphabet are
/// taken; any other is refused, shown escaped.
#include <string>
#include <string_view>

namespace rockbench::report {

/// Most characters of an engine name read back.
inline constexpr size_t kMaxEngineNameChars = 64;

/// "reference", or 1 to kMaxEngineNameChars lower-case letters, digits and '_' starting with a
/// letter: the rule of [external.<name>], which the built-in engines' names follow too.
bool IsEngineName(std::string_view name);

/// Throws std::runtime_error "WHERE: \"NAME\" is not an engine name (expected ...)" with the name
/// escaped and cut (Excerpt) when it is not IsEngineName.
void RequireEngineName(const std::string& name, const std::string& where);

}  // namespace rockbench::report
