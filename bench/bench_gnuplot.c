/* -----------------------------------------------------------------------------
 * Lignum benchmarks: writing and running a gnuplot script (bench_gnuplot.h).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include "bench_gnuplot.h"

#include <stdlib.h>
#include <string.h>

static int GnuplotOnPath(void)
{
  const char *path = getenv("PATH");
  char buf[4096];
  const char *s = path, *e;
  if (path == NULL) return 0;
  while (*s) {
    size_t n;
    FILE *fp;
    e = strchr(s, ':');
    n = e ? (size_t)(e - s) : strlen(s);
    if (n > 0 && n + 10 < sizeof buf) {
      memcpy(buf, s, n);
      strcpy(buf + n, "/gnuplot");
      if ((fp = fopen(buf, "r")) != NULL) {
        fclose(fp);
        return 1;
      }
    }
    if (!e) break;
    s = e + 1;
  }
  return 0;
}

FILE *bench_gnuplot_open(const char *prog, const char *png, char *script,
                         size_t len)
{
  FILE *fp;
  if (!GnuplotOnPath()) {
    printf("\nNote: gnuplot is not on PATH; no figure drawn (install gnuplot-nox).\n");
    return NULL;
  }
  if (strlen(png) + 4 > len || strchr(png, '"') || strchr(png, '\'')) {
    fprintf(stderr, "%s: unusable PNG path '%s'\n", prog, png);
    return NULL;
  }
  snprintf(script, len, "%s.gp", png);
  fp = fopen(script, "w");
  if (fp == NULL) perror(script);
  return fp;
}

void bench_gnuplot_run(const char *prog, FILE *fp, const char *script,
                       const char *png)
{
  char cmd[8300];
  int rc;
  if (fclose(fp) != 0) {
    perror(script);
    return;
  }
  snprintf(cmd, sizeof cmd, "gnuplot '%s'", script);
  rc = system(cmd);
  if (rc != 0)
    fprintf(stderr, "%s: gnuplot failed (status %d); script %s\n", prog, rc, script);
  else
    printf("\nFigure: %s (gnuplot script %s)\n", png, script);
}
