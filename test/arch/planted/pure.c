/* planted: a pure helper that includes the memory record's header */
#if 0
#include "lgn_impl.h"
#endif
int plantPure(void);
int plantPure(void) { return 0; }
