/* -----------------------------------------------------------------------------
 * Planar mechanisms on the planar groups (lignum_planar.h,
 * models/planar_mechanisms.c), on SE(2) and on R^2 x SO(2) bodies:
 *  (a) Andrews' squeezing mechanism (7 bodies, 10 revolute joints, a
 *      spring and a motor) under error control, BDF5 and the modified
 *      generalized-alpha, against the Test Set's reference at t = 0.03
 *      (PSIDE at tol 1e-14; the Test Set's R^7 joint angles from the body
 *      angles): the mixed error of the angles within a small multiple of
 *      tol: within 5 max(e_R, 1 / l) tol, e_R tol the error of the Test
 *      Set's own R^7 formulation (bench/suite/suite_problems.c) run at
 *      the same tol and l the shortest lever of the mechanism (the crank,
 *      7 mm): the tolerance bounds the bodies' positions in metres, which
 *      fix a body's angle only to tol / l (the R^7 model's tol bounds the
 *      angles themselves);
 *  (b) the slider-crank (gravity, a rotational spring-damper, a
 *      spring-damper, a prismatic joint) under error control against the
 *      same mechanism written separately on R^3 joint coordinates (hand
 *      derived M, g, Phi, B) at BDF5, tol 1e-12, with the same bound (l =
 *      0.2 m, the crank);
 *  (c) orders from fits over several fixed steps: the modified
 *      generalized-alpha 2 (slider-crank and Andrews), BDF2 and BDF3 k
 *      (slider-crank, history started under error control), +- 0.15.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "models/planar_mechanisms.h"
#include "suite_problem.h"

#define ANDREWS_LMIN 7e-3 /* the crank rr of andrews.f [m]     */
#define SLIDER_LMIN  0.2  /* the crank of the slider-crank [m] */

static int failures = 0;

static void Check(const char *what, double err, double tol)
{
  const int ok = err <= tol;
  printf("%-66s %.3e (bound %.1e) %s\n", what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

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

/* ---- Andrews on R^7 (bench/suite's model: row-major M and B) ------------- */

static int RnMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  double Mr[49];
  int i, j;
  (void)ud;
  SUITE_ANDREWS.mass(t, N_VGetArrayPointer(q), Mr);
  for (i = 0; i < 7; i++)
    for (j = 0; j < 7; j++) SM_ELEMENT_D(M, i, j) = Mr[7 * i + j];
  return 0;
}

static int RnForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)ud;
  SUITE_ANDREWS.force(t, N_VGetArrayPointer(q), N_VGetArrayPointer(v), N_VGetArrayPointer(g));
  return 0;
}

static int RnConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  (void)ud;
  SUITE_ANDREWS.constraints(t, N_VGetArrayPointer(q), N_VGetArrayPointer(phi));
  return 0;
}

static int RnJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  double Br[42];
  int i, j;
  (void)ud;
  SUITE_ANDREWS.jacobian(t, N_VGetArrayPointer(q), Br);
  for (i = 0; i < 6; i++)
    for (j = 0; j < 7; j++) SM_ELEMENT_D(B, i, j) = Br[7 * i + j];
  return 0;
}

static int RnAndrewsModel(void *mem, void *model)
{
  int flag = LGNSetMassFn(mem, RnMass);
  (void)model;
  if (!flag) flag = LGNSetForceFn(mem, RnForce);
  if (!flag) flag = LGNSetConstraints(mem, 6, RnConstr, RnJac);
  return flag;
}

static double RnAndrews(SUNContext ctx, LGNGroup R7, const PlanarRun *r)
{
  sunrealtype q[7], v[7];
  const int flag = planar_integrate(ctx, R7, 6, RnAndrewsModel, NULL, SUITE_ANDREWS.q0,
                                    SUITE_ANDREWS.v0, r, q, v, NULL, NULL);
  return flag ? NAN : Mixed(q, PLANAR_ANDREWS_Q_REF, 7);
}

/* the slider-crank on R^3 */
static double RnSliderCrank(SUNContext ctx, LGNGroup R3, const PlanarRun *r, const double *x_ref)
{
  sunrealtype q0[3], v0[3], q[3], v[3];
  int flag;
  rn_slider_crank_start(q0, v0);
  flag = planar_integrate(ctx, R3, 2, rn_slider_crank_set_model_fn, NULL, q0, v0, r, q, v, NULL,
                          NULL);
  return flag ? NAN : Mixed(q, x_ref, 3);
}

/* Andrews on the body group: the mixed error of the angles at t = 0.03 */
static double Andrews(SUNContext ctx, LGNGroup body, const PlanarRun *r, long *ns)
{
  PlanarMechanism pm;
  sunrealtype q0[21], v0[21], q[21], v[21];
  double ang[7], rate[7];
  int flag;
  if (planar_andrews(body, &pm, q0, v0) != 0) return NAN;
  flag = planar_integrate(ctx, pm.G, pm.m, planar_set_model_fn, &pm, q0, v0, r, q, v, ns, NULL);
  planar_andrews_angles(&pm, q, v, ang, rate);
  planar_free(&pm);
  return flag ? NAN : Mixed(ang, PLANAR_ANDREWS_Q_REF, 7);
}

/* the slider-crank on the body group against the reference x_ref */
static double SliderCrank(SUNContext ctx, LGNGroup body, const PlanarRun *r, const double *x_ref,
                          long *ns)
{
  PlanarMechanism pm;
  sunrealtype q0[9], v0[9], q[9], v[9];
  double x[3];
  int flag;
  if (planar_slider_crank(body, &pm, q0, v0) != 0) return NAN;
  flag = planar_integrate(ctx, pm.G, pm.m, planar_set_model_fn, &pm, q0, v0, r, q, v, ns, NULL);
  planar_slider_crank_coords(q, x);
  planar_free(&pm);
  return flag ? NAN : Mixed(x, x_ref, 3);
}

int main(void)
{
  SUNContext ctx;
  LGNGroup body[2], R3, R7;
  const char *gname[2] = {"SE(2)", "R2xSO(2)"};
  double xref[3];
  char what[128];
  int gi, k, i;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body[0] = LGNGroup_SE2();
  body[1] = LGNGroup_R2xSO2();
  R3      = LGNGroup_Rn(3);
  R7      = LGNGroup_Rn(7);
  { /* the slider-crank's reference on R^3 */
    sunrealtype q0[3], v0[3], q[3], v[3];
    PlanarRun r = {5, 1, 1e-12, 0, 0, 1.0};
    rn_slider_crank_start(q0, v0);
    if (planar_integrate(ctx, R3, 2, rn_slider_crank_set_model_fn, NULL, q0, v0, &r, q, v, NULL,
                         NULL) != 0)
      return 1;
    for (i = 0; i < 3; i++) xref[i] = q[i];
  }
  for (gi = 0; gi < 2; gi++) {
    /* (a) Andrews against the Test Set, and against R^7 at the same tol */
    for (k = 0; k < 3; k++) {
      const double tol = k == 1 ? 1e-8 : 1e-6;
      PlanarRun r = {k == 2 ? 0 : 5, 1, tol, 0, 0, 0.03};
      long ns;
      const double e = Andrews(ctx, body[gi], &r, &ns), en = RnAndrews(ctx, R7, &r);
      snprintf(what, sizeof what, "(a) Andrews %s, %s, tol %.0e: error/tol (R^7: %.0f)",
               gname[gi], k == 2 ? "gen-alpha" : "BDF5", tol, en / tol);
      Check(what, e / tol, 5 * fmax(en / tol, 1 / ANDREWS_LMIN));
    }
    /* (b) the slider-crank against its R^3 form (tol 1e-12), and the R^3
     * form at the same tol */
    for (k = 0; k < 2; k++) {
      PlanarRun r = {k == 0 ? 5 : 0, 1, 1e-8, 0, 0, 1.0};
      long ns;
      const double e = SliderCrank(ctx, body[gi], &r, xref, &ns);
      const double en = RnSliderCrank(ctx, R3, &r, xref);
      snprintf(what, sizeof what, "(b) slider-crank %s, %s, tol 1e-8: error/tol (R^3: %.0f)",
               gname[gi], k == 0 ? "BDF5" : "gen-alpha", en / 1e-8);
      Check(what, e / 1e-8, 5 * fmax(en / 1e-8, 1 / SLIDER_LMIN));
    }
    /* (c) orders from fits */
    {
      const int ords[3] = {0, 2, 3};
      for (k = 0; k < 3; k++) {
        double hs[4], es[4], p;
        for (i = 0; i < 4; i++) {
          PlanarRun r = {ords[k], 0, 0, 0.005 / (1 << i), 0.05, 1.0};
          hs[i] = r.h;
          es[i] = SliderCrank(ctx, body[gi], &r, xref, NULL);
        }
        p = Slope(hs, es, 4);
        snprintf(what, sizeof what, "(c) slider-crank %s, %s: |fitted order - %d| (%.2f)",
                 gname[gi], ords[k] == 0 ? "gen-alpha" : ords[k] == 2 ? "BDF2" : "BDF3",
                 ords[k] == 0 ? 2 : ords[k], p);
        Check(what, fabs(p - (ords[k] == 0 ? 2 : ords[k])), 0.15);
      }
    }
    {
      double hs[3], es[3], p;
      for (i = 0; i < 3; i++) {
        PlanarRun r = {0, 0, 0, 5e-5 / (1 << i), 0, 0.03};
        hs[i] = r.h;
        es[i] = Andrews(ctx, body[gi], &r, NULL);
      }
      p = Slope(hs, es, 3);
      snprintf(what, sizeof what, "(c) Andrews %s, gen-alpha: |fitted order - 2| (%.2f)",
               gname[gi], p);
      Check(what, fabs(p - 2), 0.15);
    }
  }
  LGNGroup_Destroy(body[0]);
  LGNGroup_Destroy(body[1]);
  LGNGroup_Destroy(R3);
  LGNGroup_Destroy(R7);
  SUNContext_Free(&ctx);
  printf("%s: %d failure(s)\n", failures ? "FAILED" : "PASSED", failures);
  return failures ? 1 : 0;
}
