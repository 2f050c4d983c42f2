// A shared library named like a plugin but without LAYERS_PLUGIN: the
// loader must say that the entry point is missing.
extern "C" int layers_test_not_an_entry_point(int x) { return x + 1; }
