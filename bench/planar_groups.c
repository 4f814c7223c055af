/* -----------------------------------------------------------------------------
 * Which planar group for bodies, SE(2) or R^2 x SO(2)? (lignum_planar.h)
 * Error at equal fixed steps and CPU time of the modified generalized-alpha
 * (rho_inf 0.9, exact kinematics) and BDF2 / BDF3 (history started under
 * error control to t = 0.05 s, resp. 0.001 s for Andrews) on
 *   the slider-crank of models/planar_mechanisms.c, t in [0, 1],
 *     against the R^3 joint-coordinate model at BDF5, tol 1e-12 (also run
 *     at the same steps: the classical formulation as a third column);
 *   Andrews' squeezing mechanism, t in [0, 0.03], against the Test Set.
 * The error is the mixed error of the joint coordinates, max |x - x_ref| /
 * (1 + |x_ref|). Prints a table and writes planar_groups.csv; the fitted
 * orders over the step sizes are printed too.
 *   build/bench/planar_groups [--csv FILE] [--quick]
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "models/planar_mechanisms.h"

static double Cpu(void) { return (double)clock() / CLOCKS_PER_SEC; }

static double Mixed(const double *x, const double *ref, int n)
{
  double e = 0;
  int i;
  for (i = 0; i < n; i++) e = fmax(e, fabs(x[i] - ref[i]) / (1 + fabs(ref[i])));
  return e;
}

static double Slope(const double *h, const double *e, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i;
  for (i = 0; i < n; i++) {
    const double a = log(h[i]), b = log(e[i]);
    sx += a; sy += b; sxx += a * a; sxy += a * b;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int main(int argc, char **argv)
{
  const char *csv = "planar_groups.csv";
  const int methods[3] = {0, 2, 3};
  const char *mname[3] = {"mod. gen-alpha", "BDF2", "BDF3"};
  int quick = 0, p, mi, gi, k, i;
  SUNContext ctx;
  LGNGroup body[2], R3;
  const char *gname[3] = {"SE(2)", "R2xSO(2)", "R^3 (joint coord.)"};
  double scref[3];
  FILE *f;
  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv = argv[++i];
    else if (strcmp(argv[i], "--quick") == 0) quick = 1;
  }
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body[0] = LGNGroup_SE2();
  body[1] = LGNGroup_R2xSO2();
  R3      = LGNGroup_Rn(3);
  f       = fopen(csv, "w");
  if (f == NULL) return 1;
  fprintf(f, "problem,group,method,h,steps,newton_iters,cpu_s,error\n");
  { /* the slider-crank's reference */
    sunrealtype q0[3], v0[3], q[3], v[3];
    PlanarRun r = {5, 1, 1e-12, 0, 0, 1.0};
    rn_slider_crank_start(q0, v0);
    if (planar_integrate(ctx, R3, 2, rn_slider_crank_set_model_fn, NULL, q0, v0, &r, q, v, NULL,
                         NULL) != 0)
      return 1;
    for (i = 0; i < 3; i++) scref[i] = q[i];
  }
  for (p = 0; p < 2; p++) {
    const int nh = quick ? 3 : 5;
    const double h0 = p == 0 ? 0.01 : 1e-4;
    printf("\n%s: mixed error of the joint coordinates at t_end, fixed steps\n",
           p == 0 ? "Slider-crank, t = 1" : "Andrews' mechanism, t = 0.03");
    printf("%-16s %-19s %9s %8s %8s %9s %10s\n", "method", "group", "h", "steps", "Newton",
           "CPU [s]", "error");
    for (mi = 0; mi < 3; mi++)
      for (gi = 0; gi < (p == 0 ? 3 : 2); gi++) {
        double hs[8], es[8];
        for (k = 0; k < nh; k++) {
          PlanarMechanism pm;
          sunrealtype q0[21], v0[21], q[21], v[21];
          double x[7], rate[7], t0, t1, err;
          long ns = 0, nn = 0;
          int flag;
          PlanarRun r = {methods[mi], 0, 0, h0 / (1 << k), p == 0 ? 0.05 : 0.001,
                         p == 0 ? 1.0 : 0.03};
          if (gi == 2) {
            rn_slider_crank_start(q0, v0);
            t0   = Cpu();
            flag = planar_integrate(ctx, R3, 2, rn_slider_crank_set_model_fn, NULL, q0, v0, &r,
                                    q, v, &ns, &nn);
            t1   = Cpu();
            for (i = 0; i < 3; i++) x[i] = q[i];
          } else {
            if ((p == 0 ? planar_slider_crank(body[gi], &pm, q0, v0)
                        : planar_andrews(body[gi], &pm, q0, v0)) != 0)
              return 1;
            t0   = Cpu();
            flag = planar_integrate(ctx, pm.G, pm.m, planar_set_model_fn, &pm, q0, v0, &r, q, v,
                                    &ns, &nn);
            t1   = Cpu();
            if (p == 0) planar_slider_crank_coords(q, x);
            else planar_andrews_angles(&pm, q, v, x, rate);
            planar_free(&pm);
          }
          err = flag ? NAN : p == 0 ? Mixed(x, scref, 3) : Mixed(x, PLANAR_ANDREWS_Q_REF, 7);
          hs[k] = r.h;
          es[k] = err;
          printf("%-16s %-19s %9.3g %8ld %8ld %9.4f %10.3e\n", mname[mi], gname[gi], r.h, ns, nn,
                 t1 - t0, err);
          fprintf(f, "%s,%s,%s,%g,%ld,%ld,%.6f,%.6e\n", p == 0 ? "slider-crank" : "andrews",
                  gname[gi], mname[mi], r.h, ns, nn, t1 - t0, err);
        }
        printf("%-16s %-19s fitted order over the steps: %.2f\n", mname[mi], gname[gi],
               Slope(hs, es, nh));
      }
  }
  fclose(f);
  LGNGroup_Destroy(body[0]);
  LGNGroup_Destroy(body[1]);
  LGNGroup_Destroy(R3);
  SUNContext_Free(&ctx);
  return 0;
}
