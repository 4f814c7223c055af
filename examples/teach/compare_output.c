/* -----------------------------------------------------------------------------
 * Compare an example's output with its answer file, as SUNDIALS' test
 * runner does:
 *
 *   compare_output <output> <answer> [rtol [atol [itol]]]
 *
 * Both files are split into lines and each line into fields at white space.
 * They must have the same number of lines and, line by line, the same
 * number of fields. A field that reads entirely as a number in both files
 * (strtod) passes if |a - b| <= atol + rtol |b| (b from the answer file;
 * defaults rtol = 1e-5, atol = 1e-6), except that a field written as an
 * integer in both (counters: steps, Newton iterations) passes if
 * |a - b| <= itol |b| (default 0.1: counts of
 * iterations and adaptive steps move with round-off); any other field must
 * be equal as text. Prints every difference; exit status 0 if none, 1 otherwise.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXLINE 4096

/* Next field of *s (advanced past it) into buf; 0 at the end of the line. */
static int NextField(const char **s, char *buf, size_t len)
{
  size_t n = 0;
  while (**s && isspace((unsigned char)**s)) (*s)++;
  if (!**s) return 0;
  while (**s && !isspace((unsigned char)**s)) {
    if (n + 1 < len) buf[n++] = **s;
    (*s)++;
  }
  buf[n] = '\0';
  return 1;
}

static int IsInteger(const char *s)
{
  if (*s == '-' || *s == '+') s++;
  if (!*s) return 0;
  for (; *s; s++)
    if (!isdigit((unsigned char)*s)) return 0;
  return 1;
}

static int IsNumber(const char *s, double *x)
{
  char *end;
  *x = strtod(s, &end);
  return end != s && *end == '\0';
}

int main(int argc, char **argv)
{
  FILE *fo, *fa;
  char lo[MAXLINE], la[MAXLINE], wo[MAXLINE], wa[MAXLINE];
  double rtol = 1e-5, atol = 1e-6, itol = 0.1;
  long line = 0, ndiff = 0;

  if (argc < 3 || argc > 6) {
    fprintf(stderr, "usage: %s output answer [rtol [atol [itol]]]\n", argv[0]);
    return 2;
  }
  if (argc > 3) rtol = atof(argv[3]);
  if (argc > 4) atol = atof(argv[4]);
  if (argc > 5) itol = atof(argv[5]);
  fo = fopen(argv[1], "r");
  fa = fopen(argv[2], "r");
  if (fo == NULL || fa == NULL) {
    fprintf(stderr, "compare_output: cannot open %s\n", fo == NULL ? argv[1] : argv[2]);
    if (fo) fclose(fo);
    if (fa) fclose(fa);
    return 2;
  }
  for (;;) {
    const char *po, *pa;
    int eo = fgets(lo, sizeof lo, fo) == NULL, ea = fgets(la, sizeof la, fa) == NULL, field = 0;
    line++;
    if (eo || ea) {
      if (eo != ea) {
        printf("line %ld: %s ends first\n", line, eo ? "the output" : "the answer file");
        ndiff++;
      }
      break;
    }
    po = lo;
    pa = la;
    for (;;) {
      int ho = NextField(&po, wo, sizeof wo), ha = NextField(&pa, wa, sizeof wa);
      double a, b;
      field++;
      if (!ho && !ha) break;
      if (ho != ha) {
        printf("line %ld: different number of fields\n  output: %s  answer: %s", line, lo, la);
        ndiff++;
        break;
      }
      if (IsNumber(wo, &a) && IsNumber(wa, &b)) {
        const double tol = IsInteger(wo) && IsInteger(wa) ? itol * fabs(b) : atol + rtol * fabs(b);
        if (!(fabs(a - b) <= tol)) {
          printf("line %ld, field %d: %s against %s (|diff| %.3e > %.3e)\n", line, field, wo,
                 wa, fabs(a - b), tol);
          ndiff++;
        }
      } else if (strcmp(wo, wa) != 0) {
        printf("line %ld, field %d: '%s' against '%s'\n", line, field, wo, wa);
        ndiff++;
      }
    }
  }
  fclose(fo);
  fclose(fa);
  printf("compare_output: %ld difference(s) (rtol %g, atol %g, itol %g)\n", ndiff, rtol, atol, itol);
  return ndiff == 0 ? 0 : 1;
}
