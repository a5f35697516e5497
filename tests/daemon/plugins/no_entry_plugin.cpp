// A shared library that is not a robotd plugin: it exports a function, but not the entry symbol.
extern "C" __attribute__((visibility("default"))) int robotd_not_a_driver() { return 42; }
