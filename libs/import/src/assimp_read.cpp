// Reading a file through assimp with its warnings captured (see
// assimp_read.h).
#include "assimp_read.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>

#include <filesystem>
#include <mutex>
#include <regex>
#include <vector>

#include "declared_counts.h"
#include "file_names.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"

namespace layers::import::detail {
namespace {

// Keeps every warning and error assimp logs while attached.
class Captured : public Assimp::LogStream {
 public:
  explicit Captured(std::vector<std::string>& into) : into_(into) {}
  void write(const char* message) override { into_.emplace_back(message); }

 private:
  std::vector<std::string>& into_;
};

std::mutex& assimp_mutex() {
  static std::mutex m;
  return m;
}

// A .gltf names its buffers and images by URI; assimp opens them itself,
// and a FIFO among them would block it forever. Each file one names (not a
// data: URI) must be a regular file, checked before assimp opens any.
void check_gltf_uris(const std::string& path) {
  namespace fs = std::filesystem;
  if (lower_extension(path) != ".gltf") return;
  const std::string text = read_text_file(path);
  static const std::regex uri(R"re("uri"\s*:\s*"([^"]*)")re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), uri); it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1].str();
    if (name.rfind("data:", 0) == 0) continue;
    const fs::path file = fs::path(path).parent_path() / name;
    std::error_code ec;
    const auto status = fs::status(file, ec);
    if (fs::exists(status) && !fs::is_regular_file(status))
      throw InputError(path, "uri", "buffers and images that are regular files",
                       "'" + name + "', " + (fs::is_directory(status) ? "a folder" : "a pipe, socket or device"));
  }
}

}  // namespace

const aiScene* read_with_assimp(Assimp::Importer& importer, const std::string& path, unsigned flags,
                                const std::string& what) {
  check_gltf_uris(path);
  check_declared_counts(path);
  std::vector<std::string> said;
  const aiScene* scene = nullptr;
  {
    std::lock_guard<std::mutex> lock(assimp_mutex());
    Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
    // The logger owns its streams and deletes them in kill().
    Assimp::DefaultLogger::get()->attachStream(new Captured(said), Assimp::Logger::Warn | Assimp::Logger::Err);
    // Validation first: assimp's own post-processing steps (triangulation,
    // sorting) read face indices unchecked, and a damaged file with an index
    // past its vertices crashed them (the importer fuzzer, a mutated PLY).
    scene = importer.ReadFile(path, flags | aiProcess_ValidateDataStructure);
    Assimp::DefaultLogger::kill();
  }
  if (!scene || !scene->mRootNode) throw InputError(path, "", what, std::string("'") + importer.GetErrorString() + "'");
  for (const std::string& s : said)
    if (s.find("out-of-range indices") != std::string::npos)
      throw InputError(path, "faces", "vertex indices within each mesh's vertices",
                       "faces with indices out of range (assimp would drop them)");
  return scene;
}

}  // namespace layers::import::detail
