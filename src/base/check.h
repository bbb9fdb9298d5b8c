/* check: CHECK(cond) states an invariant of the program (not a property of
 * the input, which gets a message and -1): when it does not hold, the
 * program prints file, line and the condition and aborts.  Always on, so
 * keep conditions cheap and out of the transport kernel's inner loop. */
#ifndef SKINBAKE_CHECK_H
#define SKINBAKE_CHECK_H
#include "base/util.h"

#define CHECK(cond) ((cond) ? (void)0 : fatalx("%s:%d: invariant failed: %s", __FILE__, __LINE__, #cond))

/* DCHECK(cond): an invariant checked only in debug builds (./configure
 * --enable-debug defines SKINBAKE_DEBUG), for the transport kernel's inner
 * loop: photon weights, unit direction cosines, energy booked.  The
 * condition is not evaluated otherwise; keep it free of side effects. */
#ifdef SKINBAKE_DEBUG
#define DCHECK(cond) CHECK(cond)
#else
#define DCHECK(cond) ((void)0)
#endif
#endif
