// Reading a file through assimp with its warnings captured (see
// assimp_read.h).
#include "assimp_read.h"

#include <assimp/scene.h>
#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>

#include <mutex>
#include <vector>

#include "layers/core/error.h"

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

}  // namespace

const aiScene* read_with_assimp(Assimp::Importer& importer, const std::string& path, unsigned flags,
                                const std::string& what) {
  std::vector<std::string> said;
  const aiScene* scene = nullptr;
  {
    std::lock_guard<std::mutex> lock(assimp_mutex());
    Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
    // The logger owns its streams and deletes them in kill().
    Assimp::DefaultLogger::get()->attachStream(new Captured(said), Assimp::Logger::Warn | Assimp::Logger::Err);
    scene = importer.ReadFile(path, flags);
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
