/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: which SUNDIALS build this
 * process loaded (Debian's packages or bench/build-ida-O2's), so that a
 * table is never labelled with the wrong one.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_SUITE_SUNDIALS_H
#define LGN_SUITE_SUNDIALS_H

#include <stdio.h>

/* From /proc/self/maps: "debian" when every SUNDIALS library of the timed
 * code (IDA, the dense and sparse matrices and solvers, the serial vector)
 * mapped comes from /usr/lib or /lib, "O2" when every one comes from a
 * directory whose parent holds bench/build-ida-O2's stamp
 * lignum-ida-O2.stamp, "mixed" otherwise, "unknown" without /proc. The
 * libraries found are listed on out (NULL: not). */
const char *suite_sundials_build(FILE *out);

#endif
