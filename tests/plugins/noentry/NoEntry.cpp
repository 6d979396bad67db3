/// A shared library that is not a Fascia plugin: no fascia_plugin_info().
extern "C" __attribute__((visibility("default"))) int fascia_test_not_a_plugin() { return 42; }
