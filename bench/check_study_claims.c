/* Reads heavy_top_study.csv (bench/heavy_top_study) and asserts what the
 * study finds, computed from the data (nothing hard-coded but the claims):
 *  1. order 2.0 +- 0.1 in the centre-of-mass error between the two smallest
 *     step sizes, for every method / constraint / rho_inf that runs there;
 *  2. index 3: exact generalized-alpha (rho_inf 0.9) at least 7x more
 *     accurate than simplified at every h <= 1.25e-3;
 *  3. index 3, undamped Newmark: exact kinematics runs on [0, 1] s at every
 *     h <= 1e-3, simplified fails at every h;
 *  4. Newton iterations: exact <= simplified at every h, for gen-alpha(0.9)
 *     at index 3 and for Newmark at index 2, and mod. LGNM (index 2) needs
 *     no more than conventional Euler-parameter Newmark (index 2).
 * Usage: check_study_claims FILE.csv */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXROWS 1024

typedef struct {
  char method[32], status[40];
  int constraints;
  double rho, h, err_com, nps;
} Row;

static Row rows[MAXROWS];
static int nrows = 0, failures = 0, checks = 0;

static void Check(int ok, const char *what)
{
  checks++;
  if (!ok) failures++;
  printf("%s %s\n", ok ? "ok  " : "FAIL", what);
}

/* Copy a field, truncated to the destination (CSV fields here are short). */
static void CopyField(char *dst, size_t size, const char *src)
{
  size_t i;
  for (i = 0; i + 1 < size && src[i] != '\0'; i++) dst[i] = src[i];
  dst[i] = '\0';
}

/* Parse one CSV line with possibly empty fields. */
static int ParseLine(char *line, Row *r)
{
  char *f[12];
  int n = 0;
  char *p = line;
  while (n < 12) {
    f[n++] = p;
    p = strchr(p, ',');
    if (p == NULL) break;
    *p++ = '\0';
  }
  if (n != 12) return 1;
  f[11][strcspn(f[11], "\r\n")] = '\0';
  CopyField(r->method, sizeof r->method, f[0]);
  r->constraints = atoi(f[1]);
  r->rho = f[2][0] ? atof(f[2]) : -1.0;
  r->h = atof(f[3]);
  r->err_com = f[4][0] ? atof(f[4]) : -1.0;
  r->nps = f[9][0] ? atof(f[9]) : -1.0;
  CopyField(r->status, sizeof r->status, f[11]);
  return 0;
}

static const Row *Find(const char *method, int constraints, double rho, double h)
{
  int i;
  for (i = 0; i < nrows; i++)
    if (!strcmp(rows[i].method, method) && rows[i].constraints == constraints &&
        fabs(rows[i].rho - rho) < 1e-12 && fabs(rows[i].h / h - 1.0) < 1e-9)
      return &rows[i];
  return NULL;
}

static int Ok(const Row *r) { return r != NULL && !strcmp(r->status, "ok"); }

int main(int argc, char **argv)
{
  const char *header = "method,constraints,rho_inf,h,err_com,err_rot,err_omega,"
                       "err_lambda,err_com_max,newton_per_step,steps,status";
  char line[1024], what[512];
  double hs[16], hmin1, hmin2;
  int nh = 0, i, j;
  FILE *fp;

  if (argc < 2 || (fp = fopen(argv[1], "r")) == NULL) {
    fprintf(stderr, "usage: check_study_claims FILE.csv (cannot open)\n");
    return 2;
  }
  if (!fgets(line, sizeof line, fp) || strncmp(line, header, strlen(header))) {
    fprintf(stderr, "bad header\n");
    return 2;
  }
  while (nrows < MAXROWS && fgets(line, sizeof line, fp))
    if (ParseLine(line, &rows[nrows]) == 0) nrows++;
  fclose(fp);

  /* the step sizes, largest first */
  for (i = 0; i < nrows; i++) {
    for (j = 0; j < nh && fabs(hs[j] / rows[i].h - 1.0) > 1e-9; j++) {}
    if (j == nh && nh < 16) hs[nh++] = rows[i].h;
  }
  for (i = 0; i < nh; i++)
    for (j = i + 1; j < nh; j++)
      if (hs[j] > hs[i]) { double t = hs[i]; hs[i] = hs[j]; hs[j] = t; }
  if (nh < 3) {
    fprintf(stderr, "need at least three step sizes\n");
    return 2;
  }
  hmin1 = hs[nh - 2];
  hmin2 = hs[nh - 1];

  /* 1. observed order between the two smallest step sizes */
  for (i = 0; i < nrows; i++) {
    const Row *a, *b;
    double order;
    if (fabs(rows[i].h / hmin1 - 1.0) > 1e-9) continue;
    a = &rows[i];
    b = Find(a->method, a->constraints, a->rho, hmin2);
    if (!Ok(a) || !Ok(b)) continue;
    order = log(a->err_com / b->err_com) / log(hmin1 / hmin2);
    snprintf(what, sizeof what, "order %-20.31s idx%d rho %-4g: %.3f = 2.0 +- 0.1",
             a->method, a->constraints, a->rho, order);
    Check(fabs(order - 2.0) <= 0.1, what);
  }

  for (j = 0; j < nh; j++) {
    const double h = hs[j];
    const Row *s = Find("lggalpha", 3, 0.9, h), *e = Find("mod-lggalpha", 3, 0.9, h);
    const Row *ns = Find("lgnm", 3, -1.0, h), *ne = Find("mod-lgnm", 3, -1.0, h);
    const Row *n2 = Find("lgnm", 2, -1.0, h), *e2 = Find("mod-lgnm", 2, -1.0, h);
    const Row *ep2 = Find("newmark-ep", 2, -1.0, h);
    /* 2. exact vs simplified gen-alpha(0.9), index 3 */
    if (h <= 1.25e-3 * (1 + 1e-9)) {
      snprintf(what, sizeof what, "h = %.4e: mod-lggalpha(0.9) idx3 %.1fx more accurate than lggalpha (>= 7)",
               h, Ok(s) && Ok(e) ? s->err_com / e->err_com : 0.0);
      Check(Ok(s) && Ok(e) && s->err_com / e->err_com >= 7.0, what);
    }
    /* 3. undamped Newmark at index 3 */
    snprintf(what, sizeof what, "h = %.4e: lgnm idx3 fails (%.39s)", h, ns ? ns->status : "missing");
    Check(ns != NULL && !Ok(ns), what);
    if (h <= 1e-3 * (1 + 1e-9)) {
      snprintf(what, sizeof what, "h = %.4e: mod-lgnm idx3 runs (%.39s)", h, ne ? ne->status : "missing");
      Check(Ok(ne), what);
    }
    /* 4. Newton iterations */
    if (Ok(s) && Ok(e)) {
      snprintf(what, sizeof what, "h = %.4e: Newton/step mod-lggalpha %.2f <= lggalpha %.2f", h, e->nps, s->nps);
      Check(e->nps <= s->nps + 1e-9, what);
    }
    if (Ok(n2) && Ok(e2) && Ok(ep2)) {
      snprintf(what, sizeof what, "h = %.4e: Newton/step idx2 mod-lgnm %.3f <= lgnm %.3f, <= newmark-ep %.3f",
               h, e2->nps, n2->nps, ep2->nps);
      Check(e2->nps <= n2->nps + 1e-9 && e2->nps <= ep2->nps + 1e-9, what);
    }
  }
  printf("check_study_claims: %d checks, %d failures (%d rows)\n", checks, failures, nrows);
  return failures == 0 ? 0 : 1;
}
