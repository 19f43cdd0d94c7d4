#include "run/engine_registry.h"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <memory>
#include <mutex>
#include <sstream>

#include "engines/external/external_engine.h"
#include "run/reference_engine.h"
#include "scene/limits.h"
#include "util/relayed_text.h"

namespace rockbench {

namespace engine_registry {
#define ROCKBENCH_BUILT_ENGINE(name) std::unique_ptr<Engine> Make_##name();
#define ROCKBENCH_MISSING_ENGINE(name, why)
#include "engines/engine_list.inc"
#undef ROCKBENCH_BUILT_ENGINE
#undef ROCKBENCH_MISSING_ENGINE
}  // namespace engine_registry

namespace {

// The registry: the built-in engines, then the external ones as registry files and scenes name
// them. Engines live as long as the program; the list only grows, under a mutex.
struct Registry {
  std::mutex mutex;
  std::vector<RegisteredEngine> list;
  std::deque<std::unique_ptr<Engine>> owned;
  // Per external engine (same index as its entry, from first_external): what named it, and the
  // command it runs (resolved against the naming file's folder or its manifest's).
  std::vector<ExternalEngineRef> refs;
  std::vector<std::vector<std::string>> commands;
  size_t first_external = 0;
};

bool SameRef(const ExternalEngineRef& a, const ExternalEngineRef& b) {
  return a.manifest == b.manifest && a.command == b.command && a.base_dir == b.base_dir;
}

// Both empty, or the same file however named.
bool SameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  if (a.empty() || b.empty()) return a.empty() && b.empty();
  std::error_code ec1, ec2;
  const std::filesystem::path ca = std::filesystem::weakly_canonical(a, ec1);
  const std::filesystem::path cb = std::filesystem::weakly_canonical(b, ec2);
  return !ec1 && !ec2 && ca == cb;
}

// Adds an external engine (the caller holds the mutex). A name taken by a built-in engine, or by
// another external engine named differently, is an error naming both places. `from_scene`: a
// scene brought it (it awaits the user's word); the same engine a registry file names is the
// registry's.
void AddExternal(Registry& r, const ExternalEngineRef& ref, bool from_scene) {
  for (size_t i = 0; i < r.list.size(); ++i) {
    if (r.list[i].name != ref.name) continue;
    if (i < r.first_external) {
      throw SceneError(ref.where + ": [external." + ref.name + "]: '" + ref.name +
                       "' is a built-in engine's name; give the external engine another");
    }
    const size_t k = i - r.first_external;
    if (SameRef(r.refs[k], ref)) return;
    // A scene naming an engine of a registry file: the same engine when it runs the same command
    // (the registry's copy of a scene's table, elsewhere): the registry's.
    if (from_scene && r.list[i].brought_by.empty() && SameFile(r.refs[k].manifest, ref.manifest)) {
      std::vector<std::string> command;
      try {
        command = external::LoadManifest(ref).command;
      } catch (const SceneError&) {
      }
      if (!command.empty() && command == r.commands[k]) return;
    }
    throw SceneError(ref.where + ": [external." + ref.name +
                     "]: an external engine of that name is " +
                     "already registered, differently, by " + r.refs[i - r.first_external].where);
  }
  external::ExternalManifest m = external::LoadManifest(ref);
  std::vector<std::string> command = m.command;
  RegisteredEngine e{ref.name, nullptr, m.missing_reason, "", false};
  if (from_scene) {
    e.brought_by = ref.where;
    e.awaits_user = true;
  }
  if (m.missing_reason.empty()) {
    r.owned.push_back(std::make_unique<external::ExternalEngine>(std::move(m)));
    e.engine = r.owned.back().get();
  }
  r.list.push_back(std::move(e));
  r.refs.push_back(ref);
  r.commands.push_back(std::move(command));
}

// Adds the engines of a registry file; a file that cannot be read leaves a line saying why.
void AddRegistryFile(Registry& r, const std::filesystem::path& file) {
  try {
    for (const ExternalEngineRef& ref : LoadExternalEngineRegistry(file)) {
      AddExternal(r, ref, false);
    }
  } catch (const SceneError& e) {
    r.list.push_back(RegisteredEngine{"(" + file.string() + ")", nullptr, e.what(), "", false});
    r.refs.push_back(ExternalEngineRef{});
    r.commands.emplace_back();
  }
}

Registry& TheRegistry() {
  static Registry* registry = [] {
    auto* r = new Registry;
#define ROCKBENCH_BUILT_ENGINE(name)                  \
  r->owned.push_back(engine_registry::Make_##name()); \
  r->list.push_back(RegisteredEngine{#name, r->owned.back().get(), "", "", false});
#define ROCKBENCH_MISSING_ENGINE(name, why) \
  r->list.push_back(RegisteredEngine{#name, nullptr, why, "", false});
#include "engines/engine_list.inc"
#undef ROCKBENCH_BUILT_ENGINE
#undef ROCKBENCH_MISSING_ENGINE
    r->first_external = r->list.size();
#ifdef ROCKBENCH_EXTERNAL_REGISTRY
    std::error_code ec;
    if (std::filesystem::exists(ROCKBENCH_EXTERNAL_REGISTRY, ec)) {
      AddRegistryFile(*r, ROCKBENCH_EXTERNAL_REGISTRY);
    }
#endif
    if (const char* files = std::getenv("ROCKBENCH_EXTERNAL_ENGINES")) {
      std::stringstream list(files);
      std::string file;
      while (std::getline(list, file, ':')) {
        if (!file.empty()) AddRegistryFile(*r, file);
      }
    }
    return r;
  }();
  return *registry;
}

}  // namespace

std::vector<RegisteredEngine> EngineRegistry() {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<RegisteredEngine> out;
  for (const RegisteredEngine& e : r.list) {
    if (!e.name.empty() && e.name[0] != '(') out.push_back(e);
  }
  return out;
}

void RegisterExternalEngines(const Scene& scene) {
  if (scene.external_engines.empty()) return;
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const ExternalEngineRef& ref : scene.external_engines) AddExternal(r, ref, true);
}

namespace {

// The user named `name` on the command line: a scene-brought engine of that name may run.
void GiveUsersWord(const std::string& name) {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (RegisteredEngine& e : r.list) {
    if (e.name == name) e.awaits_user = false;
  }
}

}  // namespace

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
    if (e.engine != nullptr && !e.awaits_user) names.push_back(e.name);
  }
  return names;
}

std::string OptInText(const std::string& name) {
  return "rockbench runs an engine that a scene or study brings only on your word: name it on "
         "the command line (--engines " +
         name + ") or add its [external." + name +
         "] table to a registry file you own (engines/external_engines.toml, or a file named in "
         "ROCKBENCH_EXTERNAL_ENGINES)";
}

std::string NotRunNote(const std::vector<std::string>& selected) {
  std::string out;
  for (const RegisteredEngine& e : EngineRegistry()) {
    if (!e.awaits_user || e.engine == nullptr) continue;
    if (std::find(selected.begin(), selected.end(), e.name) != selected.end()) continue;
    out += "rockbench: not run: external engine " + e.name + ", which " + e.brought_by +
           " brings ([external." + e.name + "]): " + OptInText(e.name) + "\n";
  }
  return out;
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
      throw SceneError("--engines: unknown engine '" + Excerpt(name) +
                       "' (expected 'all' or some of: " + KnownList() + ")");
    }
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    GiveUsersWord(name);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return names;
}

std::vector<std::string> ParseEnginesBesideReference(const std::string& text) {
  std::string list;
  for (size_t start = 0; start <= text.size();) {
    const size_t comma = text.find(',', start);
    const std::string name = text.substr(start, comma == std::string::npos ? comma : comma - start);
    if (!IsReference(name)) list += (list.empty() ? "" : ",") + name;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (list.empty()) return {};
  return ParseEngineList(list);
}

void CheckEngineName(const std::string& name) {
  const auto expected = [] {
    return " (expected \"reference\" or one of: " + KnownList() + ", one name per entry)";
  };
  // The reference is an engine of every build (FindEngine knows it apart from the registry).
  if (FindEngine(name) == &TheReference()) return;
  for (const RegisteredEngine& e : EngineRegistry()) {
    if (e.name != name) continue;
    if (e.engine == nullptr) {
      throw SceneError(name + " is not in this build (" + e.missing_reason + ")");
    }
    if (e.awaits_user) {
      throw SceneError(name + " is an external engine that " + e.brought_by +
                       " brings ([external." + name +
                       "]), not one you registered: " + OptInText(name));
    }
    return;
  }
  if (name == "all") {
    throw SceneError("\"all\" is not an engine name: a study lists its runs one by one" +
                     expected());
  }
  if (name.find(',') != std::string::npos) {
    throw SceneError("\"" + Excerpt(name) + "\" is not an engine name: one engine per entry" +
                     expected());
  }
  throw SceneError("unknown engine \"" + Excerpt(name) + "\"" + expected());
}

void CheckEngineTables(const Scene& scene) {
  RegisterExternalEngines(scene);
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
  Registry& r = TheRegistry();
  std::vector<RegisteredEngine> all;
  {
    std::lock_guard<std::mutex> lock(r.mutex);
    all = r.list;
  }
  for (const RegisteredEngine& e : all) {
    if (!e.name.empty() && e.name[0] == '(') {
      out += "registry " + EscapedText(e.name, 400) +
             ": not read: " + EscapedText(e.missing_reason) + "\n";
      continue;
    }
    // A manifest's version text and a registry's reasons are files' text: escaped and capped.
    if (e.engine != nullptr) {
      out += e.name + ": " + EscapedText(e.engine->version(), 400) + "\n";
    } else {
      out += e.name + ": left out of this build (" + EscapedText(e.missing_reason) + ")\n";
    }
  }
  return out;
}

std::vector<std::string> EnginesThatBuild(const Scene& scene,
                                          const std::vector<std::string>& selected,
                                          std::string* not_run) {
  std::vector<std::string> builds;
  for (const std::string& name : selected) {
    try {
      if (const Engine* engine = FindEngine(name)) CheckBuildsBodies(*engine, scene);
      builds.push_back(name);
    } catch (const SceneError& e) {
      if (not_run) *not_run += std::string("rockbench: compare: not run: ") + e.what() + "\n";
    }
  }
  return builds;
}

}  // namespace rockbench
