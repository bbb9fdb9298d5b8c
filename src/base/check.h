/* check: CHECK(cond) states an invariant of the program (not a property of
 * the input, which gets a message and -1): when it does not hold, the
 * program prints file, line and the condition and aborts.  Always on, so
 * keep conditions cheap and out of the transport kernel's inner loop. */
#ifndef SKINBAKE_CHECK_H
#define SKINBAKE_CHECK_H
#include "base/util.h"

#define CHECK(cond) ((cond) ? (void)0 : fatalx("%s:%d: invariant failed: %s", __FILE__, __LINE__, #cond))
#endif
