/* The implementation of stereoblend.h in a translation unit of its own: `make check`
   compiles it once per configuration and links it into every test of that
   configuration (tests are then compiled with -DSTEREOBLEND_IMPLEMENTATION_DONE).
   Tests that define STEREOBLEND_STATIC (they call internal functions) build their own. */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
