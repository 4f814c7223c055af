/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: which SUNDIALS build this
 * process loaded (suite_sundials.h; the convention of work_precision.c).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <string.h>

#include "suite_sundials.h"

/* The libraries the timed code loads from SUNDIALS (bench/build-ida-O2
 * builds these; the MPI vectors liblignum may load, and ARKODE, a
 * reference never timed, are not counted). */
static int IsTimedLibrary(const char *path)
{
  static const char *const LIBS[] = {
    "libsundials_ida.so", "libsundials_sunlinsoldense.so", "libsundials_sunmatrixdense.so",
    "libsundials_nvecserial.so", "libsundials_sunlinsolklu.so", "libsundials_sunmatrixsparse.so"};
  size_t i;
  for (i = 0; i < sizeof LIBS / sizeof LIBS[0]; i++)
    if (strstr(path, LIBS[i]) != NULL) return 1;
  return 0;
}

/* 1 if the directory above the library's holds the -O2 build's stamp. */
static int IsO2Library(const char *path)
{
  char stamp[4200];
  const char *slash = strrchr(path, '/');
  size_t n;
  FILE *fp;
  if (slash == NULL) return 0;
  n = (size_t)(slash - path);
  while (n > 0 && path[n - 1] != '/') n--;
  if (n == 0) return 0;
  snprintf(stamp, sizeof stamp, "%.*slignum-ida-O2.stamp", (int)n, path);
  fp = fopen(stamp, "r");
  if (fp == NULL) return 0;
  fclose(fp);
  return 1;
}

const char *suite_sundials_build(FILE *out)
{
  char line[4608], last[4608] = "";
  int deb = 0, o2 = 0, other = 0;
  FILE *fp = fopen("/proc/self/maps", "r");
  if (fp == NULL) return "unknown";
  while (fgets(line, sizeof line, fp) != NULL) {
    char *path = strchr(line, '/'), *nl;
    if (path == NULL || !IsTimedLibrary(path)) continue;
    if ((nl = strchr(path, '\n')) != NULL) *nl = '\0';
    if (strcmp(path, last) == 0) continue; /* one library maps several segments */
    snprintf(last, sizeof last, "%s", path);
    if (IsO2Library(path)) o2++;
    else if (strncmp(path, "/usr/lib/", 9) == 0 || strncmp(path, "/lib/", 5) == 0) deb++;
    else other++;
    if (out != NULL) fprintf(out, "  loaded %s\n", path);
  }
  fclose(fp);
  if (o2 > 0 && deb == 0 && other == 0) return "O2";
  if (deb > 0 && o2 == 0 && other == 0) return "debian";
  return o2 + deb + other == 0 ? "unknown" : "mixed";
}
