// Plugin discovery and loading with dlopen (see plugin_loader.h).
#include "layers/zoo/plugin_loader.h"

#include <dlfcn.h>
#include <elf.h>
#include <link.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "layers/core/error.h"
#include "layers/core/install_paths.h"
#include "layers/zoo/plugin_abi.h"
#include "layers/zoo/plugin_hash.h"

namespace fs = std::filesystem;

namespace layers::zoo {

// The loader's side of a Registry: which plugin is registering, and undoing
// its registrations when it fails.
struct detail::RegistryLoading {
  static void begin(Registry& r, const std::string& path) {
    r.loading_ = path;
    r.plugin_errors_.clear();
  }
  static std::vector<std::string> models_of(const Registry& r, const std::string& path) {
    std::vector<std::string> out;
    for (const auto& [name, entry] : r.entries_)
      if (entry.plugin_path == path) out.push_back(name);
    return out;
  }
  static void remove_models_of(Registry& r, const std::string& path) {
    for (auto it = r.entries_.begin(); it != r.entries_.end();)
      it = it->second.plugin_path == path ? r.entries_.erase(it) : std::next(it);
  }
  // Ends the registration; returns the errors the plugin reported.
  static std::vector<std::string> end(Registry& r) {
    r.loading_.clear();
    return std::move(r.plugin_errors_);
  }
};

namespace {

using detail::RegistryLoading;

constexpr const char* kPrefix = "liblayers_plugin_";
constexpr const char* kSuffix = ".so";

bool is_plugin_file_name(const std::string& name) {
  const std::string prefix = kPrefix, suffix = kSuffix;
  return name.size() > prefix.size() + suffix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
         name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Why the 64-bit ELF file `path` cannot be a whole shared library, or "":
// it is shorter than its own headers say (the program headers' segments and the
// section header table must lie inside the file). dlopen maps a truncated
// file and the process dies with SIGBUS on the first page past its end,
// or loads a library cut short; this is read before dlopen.
std::string elf_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!in || ec) return "cannot be read";
  Elf64_Ehdr h{};
  in.read(reinterpret_cast<char*>(&h), sizeof h);
  // Not ELF, or not 64-bit: dlopen says what it is.
  if (in.gcount() != static_cast<std::streamsize>(sizeof h) || std::memcmp(h.e_ident, ELFMAG, SELFMAG) != 0 ||
      h.e_ident[EI_CLASS] != ELFCLASS64)
    return "";
  std::uintmax_t need = sizeof h;
  const auto extent = [](std::uintmax_t offset, std::uintmax_t count, std::uintmax_t each) {
    return offset + count * each;
  };
  need = std::max<std::uintmax_t>(need, extent(h.e_phoff, h.e_phnum, h.e_phentsize));
  need = std::max<std::uintmax_t>(need, extent(h.e_shoff, h.e_shnum, h.e_shentsize));
  if (need <= size && h.e_phentsize == sizeof(Elf64_Phdr)) {
    in.seekg(static_cast<std::streamoff>(h.e_phoff));
    for (int i = 0; i < h.e_phnum && in; ++i) {
      Elf64_Phdr p{};
      in.read(reinterpret_cast<char*>(&p), sizeof p);
      if (in && p.p_type == PT_LOAD) need = std::max<std::uintmax_t>(need, p.p_offset + p.p_filesz);
    }
  }
  if (need > size)
    return "truncated: its ELF headers need " + std::to_string(need) + " bytes, the file has " + std::to_string(size);
  return "";
}

std::string canonical_or_absolute(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::canonical(p, ec);
  return ec ? fs::absolute(p).lexically_normal().string() : c.string();
}

std::vector<std::string> split_path_list(const char* value) {
  std::vector<std::string> out;
  if (!value) return out;
  std::stringstream in(value);
  std::string item;
  while (std::getline(in, item, ':'))
    if (!item.empty()) out.push_back(item);
  return out;
}

// Candidate directories in search order, each with whether it came from
// LAYERS_PLUGIN_PATH (those must exist).
std::vector<std::pair<std::string, bool>> candidate_dirs() {
  std::vector<std::pair<std::string, bool>> out;
  for (const auto& dir : split_path_list(std::getenv("LAYERS_PLUGIN_PATH"))) out.emplace_back(dir, true);
  const std::string exe_dir = executable_dir();
  if (!exe_dir.empty()) {
    out.emplace_back((fs::path(exe_dir) / "plugins").string(), false);
    out.emplace_back(exe_dir, false);
  }
  const std::string installed = installed_dir(kInstalledPluginDir);
  if (!installed.empty()) out.emplace_back(installed, false);
  return out;
}

// Distinct existing directories of `dirs`, canonical, in order.
std::vector<std::string> existing_unique(const std::vector<std::string>& dirs) {
  std::vector<std::string> out;
  for (const auto& d : dirs) {
    std::error_code ec;
    if (!fs::is_directory(d, ec)) continue;
    std::string c = canonical_or_absolute(d);
    if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  }
  return out;
}

std::vector<fs::path> plugin_files_in(const std::string& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  // Every entry named like a plugin, whatever it is: load_file refuses
  // (and so reports) a directory or a dangling link instead of skipping it.
  for (const auto& item : fs::directory_iterator(dir, ec))
    if (is_plugin_file_name(item.path().filename().string())) out.push_back(item.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The ELF type of the symbol at `address`: "function", "data object",
// "an unknown symbol type N", or "no symbol table entry".
std::string elf_symbol_kind(void* address) {
  Dl_info info{};
  void* entry = nullptr;
  if (!dladdr1(address, &info, &entry, RTLD_DL_SYMENT) || !entry) return "no symbol table entry";
  const auto* sym = static_cast<const ElfW(Sym)*>(entry);
  const int type = ELF64_ST_TYPE(sym->st_info);
  if (type == STT_FUNC || type == STT_GNU_IFUNC) return "function";
  if (type == STT_OBJECT || type == STT_TLS || type == STT_COMMON) return "a data object";
  return "an unknown symbol type " + std::to_string(type);
}

[[noreturn]] void refuse(const std::string& path, const std::string& text) {
  throw InputError::message(path, "", text);
}

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : sep) + s;
  return out;
}

// Runs the entry point with the registry in loading state and turns its
// outcome into models or an InputError (after undoing its registrations).
std::vector<std::string> register_plugin(Registry& registry, const std::string& path, PluginEntry entry) {
  const PluginAbi& host = host_plugin_abi();
  PluginAbi plugin{};
  RegistryLoading::begin(registry, path);
  int rc = entry(&host, &plugin, &registry);
  std::vector<std::string> errors = RegistryLoading::end(registry);
  std::vector<std::string> models = RegistryLoading::models_of(registry, path);
  std::string failure;
  if (rc > 0) {
    // A plugin of the v1 protocol took the host record's address for its
    // version argument and returned its own version without registering.
    failure = "built for zoo API v" + std::to_string(rc) + ", this layers expects v" +
              std::to_string(host.api_version) + "; rebuild the plugin against this layers";
  } else if (rc == kPluginRecordMismatch) {
    failure =
        "its plugin ABI record differs in size from this layers' (another plugin protocol); "
        "rebuild the plugin against this layers";
  } else if (rc == kPluginAbiMismatch) {
    failure = plugin_abi_mismatch(host, plugin);
    if (failure.empty()) failure = "refused the handshake although its ABI record matches this layers'";
  } else if (rc != 0) {
    // Errors thrown by Registry::add already start with this plugin's path.
    for (auto& e : errors)
      if (e.rfind(path + ": ", 0) == 0) e.erase(0, path.size() + 2);
    failure =
        "registration failed: " + (errors.empty() ? "entry point returned " + std::to_string(rc) : join(errors, "; "));
  } else if (models.empty()) {
    failure = "registered no models";
  }
  if (!failure.empty()) {
    RegistryLoading::remove_models_of(registry, path);
    refuse(path, failure);
  }
  return models;
}

}  // namespace

int api_version() { return static_cast<int>(host_plugin_abi().api_version); }

std::vector<std::string> plugin_search_path() {
  std::vector<std::string> dirs;
  for (const auto& [dir, from_env] : candidate_dirs()) dirs.push_back(dir);
  return existing_unique(dirs);
}

LoadedPlugin load_file(Registry& registry, const std::string& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    if (fs::is_symlink(fs::symlink_status(file, ec)) && !fs::exists(file, ec))
      refuse(file, "expected a plugin file, got a dangling symbolic link");
    if (fs::is_directory(file, ec)) refuse(file, "expected a plugin file, got a directory");
    refuse(file, fs::exists(file, ec) ? "expected a plugin file, got a special file" : "no such plugin file");
  }
  const std::string path = canonical_or_absolute(file);
  if (auto already = RegistryLoading::models_of(registry, path); !already.empty()) return {path, already};

  const bool verified = check_plugin_hash(path) == PluginHash::Verified;  // throws when the bytes changed
  if (const std::string problem = elf_problem(path); !problem.empty()) refuse(path, "cannot load plugin: " + problem);
  dlerror();
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    refuse(path, std::string("cannot load plugin: ") + (why ? why : "dlopen failed"));
  }
  dlerror();
  void* symbol = dlsym(handle, kPluginEntryPoint);
  if (!symbol) {
    dlclose(handle);
    refuse(path, std::string("not a layers plugin: no entry point '") + kPluginEntryPoint +
                     "' (define it with LAYERS_PLUGIN from layers/zoo/plugin.h)");
  }
  // Calling a data symbol would jump into data: check the ELF symbol type.
  const std::string kind = elf_symbol_kind(symbol);
  if (kind != "function") {
    dlclose(handle);
    refuse(path, std::string("not a layers plugin: entry point '") + kPluginEntryPoint +
                     "' expected a function symbol, got " + kind);
  }
  auto entry = reinterpret_cast<PluginEntry>(symbol);
  try {
    std::vector<std::string> models = register_plugin(registry, path, entry);
    // Deliberately never closed: factories and model code live in it.
    return {path, models, verified};
  } catch (...) {
    dlclose(handle);  // nothing of it is left in the registry
    throw;
  }
}

LoadReport load_all(Registry& registry, const std::vector<std::string>& directories) {
  LoadReport report;
  report.searched = existing_unique(directories);
  // Every file of each name, in search order.
  std::vector<std::string> names;
  std::map<std::string, std::vector<std::string>> files_by_name;
  for (const auto& dir : report.searched)
    for (const auto& file : plugin_files_in(dir)) {
      auto& files = files_by_name[file.filename().string()];
      if (files.empty()) names.push_back(file.filename().string());
      files.push_back(file.string());
    }
  std::error_code ec;
  const auto recorded = [&](const std::string& f) { return fs::exists(plugin_hash_file(f), ec); };
  for (const std::string& name : names) {
    const std::vector<std::string>& files = files_by_name[name];
    // The first file with a recorded hash, then the first without: a copy
    // nobody recorded does not shadow one whose bytes can be checked. A
    // refused file shadows nothing: the next one is tried.
    std::vector<std::string> order;
    for (const auto& f : files)
      if (recorded(f)) order.push_back(f);
    for (const auto& f : files)
      if (!recorded(f)) order.push_back(f);
    std::string chosen;
    std::vector<std::string> tried;
    for (const auto& f : order) {
      tried.push_back(f);
      try {
        report.loaded.push_back(load_file(registry, f));
        chosen = f;
        break;
      } catch (const std::exception& e) {
        report.problems.push_back({f, e.what()});
      }
    }
    if (chosen.empty()) continue;
    for (const auto& f : files) {
      if (std::find(tried.begin(), tried.end(), f) != tried.end()) continue;
      if (std::find(files.begin(), files.end(), f) < std::find(files.begin(), files.end(), chosen))
        report.passed_over.push_back({f, f +
                                             ": skipped although first on the plugin path: it has no recorded content "
                                             "hash and " +
                                             chosen + " has one (" + plugin_hash_file(chosen) +
                                             "); record one with layers_plugin_hash, or remove it"});
      else
        report.shadowed.push_back({f, f + ": skipped, shadowed by " + chosen});
    }
  }
  return report;
}

LoadReport load_all(Registry& registry) {
  std::vector<PluginProblem> bad_env;
  std::vector<std::string> dirs;
  for (const auto& [dir, from_env] : candidate_dirs()) {
    std::error_code ec;
    if (from_env && !fs::is_directory(dir, ec)) {
      bad_env.push_back({dir, dir + ": LAYERS_PLUGIN_PATH entry is not a directory"});
    }
    dirs.push_back(dir);
  }
  LoadReport report = load_all(registry, dirs);
  report.problems.insert(report.problems.begin(), bad_env.begin(), bad_env.end());
  return report;
}

}  // namespace layers::zoo
