// layers_plugin_hash -- records a plugin's content hash beside it, as the
// build does after linking a plugin and the install after copying it:
// FILE.hash holds the hex of the toolkit's content hash (core/checksum.h)
// of FILE's bytes, which the plugin loader checks before dlopen
// (zoo/plugin_loader.h).
//   layers_plugin_hash FILE...
#include <cstdio>
#include <exception>

#include "layers/zoo/plugin_hash.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: layers_plugin_hash FILE...\n");
    return 2;
  }
  try {
    for (int i = 1; i < argc; ++i) layers::zoo::record_plugin_hash(argv[i]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "layers_plugin_hash: %s\n", e.what());
    return 1;
  }
  return 0;
}
