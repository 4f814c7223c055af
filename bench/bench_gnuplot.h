/* -----------------------------------------------------------------------------
 * Lignum benchmarks: writing and running a gnuplot script for a PNG figure.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_BENCH_GNUPLOT_H
#define LGN_BENCH_GNUPLOT_H

#include <stdio.h>

/* Open the script "<png>.gp" (its name into script[len]) for the figure png.
 * Returns NULL, after a note, when gnuplot is not on PATH, the path is
 * unusable or the file cannot be opened; prog prefixes the messages. */
FILE *bench_gnuplot_open(const char *prog, const char *png, char *script,
                         size_t len);

/* Close the script and run gnuplot on it; say where the figure is. */
void bench_gnuplot_run(const char *prog, FILE *fp, const char *script,
                       const char *png);

#endif
