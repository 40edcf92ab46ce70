// Test library: a valid shared library that is not a Talus plugin.
extern "C" __attribute__((visibility("default"))) int talus_test_not_a_plugin() { return 42; }
