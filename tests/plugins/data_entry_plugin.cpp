// A shared library named like a plugin whose entry point symbol is data,
// not a function: the loader must refuse it by the symbol's ELF type
// instead of calling into data.
extern "C" {
__attribute__((visibility("default"))) int layers_plugin_register[4] = {1, 2, 3, 4};
}
