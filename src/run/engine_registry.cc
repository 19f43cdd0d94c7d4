#include "run/engine_registry.h"

#include <algorithm>
#include <memory>

#include "run/reference_engine.h"

namespace rockbench {

namespace engine_registry {
#define ROCKBENCH_BUILT_ENGINE(name) std::unique_ptr<Engine> Make_##name();
#define ROCKBENCH_MISSING_ENGINE(name, why)
#include "engines/engine_list.inc"
#undef ROCKBENCH_BUILT_ENGINE
#undef ROCKBENCH_MISSING_ENGINE
}  // namespace engine_registry

const std::vector<RegisteredEngine>& EngineRegistry() {
  static const std::vector<RegisteredEngine> kRegistry = [] {
    // The engines live as long as the program.
    static std::vector<std::unique_ptr<Engine>> owned;
    std::vector<RegisteredEngine> list;
#define ROCKBENCH_BUILT_ENGINE(name)               \
  owned.push_back(engine_registry::Make_##name()); \
  list.push_back(RegisteredEngine{#name, owned.back().get(), ""});
#define ROCKBENCH_MISSING_ENGINE(name, why) list.push_back(RegisteredEngine{#name, nullptr, why});
#include "engines/engine_list.inc"
#undef ROCKBENCH_BUILT_ENGINE
#undef ROCKBENCH_MISSING_ENGINE
    return list;
  }();
  return kRegistry;
}

const Engine* FindEngine(const std::string& name) {
  if (name == TheReference().name()) return &TheReference();
  for (const RegisteredEngine& e : EngineRegistry()) {
    if (e.name == name) return e.engine;
  }
  return nullptr;
}

std::vector<std::string> BuiltEngineNames() {
  std::vector<std::string> names;
  for (const RegisteredEngine& e : EngineRegistry()) {
    if (e.engine != nullptr) names.push_back(e.name);
  }
  return names;
}

namespace {

std::string KnownList() {
  std::string built, missing;
  for (const RegisteredEngine& e : EngineRegistry()) {
    std::string& list = e.engine != nullptr ? built : missing;
    list += (list.empty() ? "" : ", ") + e.name;
  }
  return built + (missing.empty() ? "" : "; left out of this build: " + missing);
}

}  // namespace

std::vector<std::string> ParseEngineList(const std::string& text) {
  if (text == "all") return BuiltEngineNames();
  std::vector<std::string> names;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    std::string name = text.substr(start, comma == std::string::npos ? comma : comma - start);
    while (!name.empty() && name.front() == ' ') name.erase(name.begin());
    while (!name.empty() && name.back() == ' ') name.pop_back();
    if (name.empty()) {
      throw SceneError("--engines: expected a comma-separated list of engines or 'all', got '" +
                       text + "'");
    }
    bool known = false;
    for (const RegisteredEngine& e : EngineRegistry()) {
      if (e.name != name) continue;
      known = true;
      if (e.engine == nullptr) {
        throw SceneError("--engines: " + name + " is not in this build (" + e.missing_reason + ")");
      }
    }
    if (!known) {
      throw SceneError("--engines: unknown engine '" + name +
                       "' (expected 'all' or some of: " + KnownList() + ")");
    }
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return names;
}

void CheckEngineTables(const Scene& scene) {
  for (const auto& [name, table] : scene.engine_tables) {
    bool known = false;
    for (const RegisteredEngine& e : EngineRegistry()) {
      if (e.name != name) continue;
      known = true;
      if (e.engine != nullptr) ResolveEngineSettings(scene, e.engine->settings_schema());
    }
    if (!known) {
      throw SceneError(table.where + ": [" + name +
                       "]: unknown table (expected a scene table: block1, block2, initial, "
                       "base, run, model, compare; or an engine's: " +
                       KnownList() + ")");
    }
  }
}

std::string EngineListText() {
  std::string out;
  for (const RegisteredEngine& e : EngineRegistry()) {
    if (e.engine != nullptr) {
      out += e.name + ": " + e.engine->version() + "\n";
    } else {
      out += e.name + ": left out of this build (" + e.missing_reason + ")\n";
    }
  }
  return out;
}

}  // namespace rockbench
