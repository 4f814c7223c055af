/* The probe of the test symbols_leak_detected: an internal function
 * exported by mistake from a library of Lignum's objects. */
__attribute__((visibility("default"))) int lgnSymbolsLeakProbe(void);

int lgnSymbolsLeakProbe(void) { return 0; }
