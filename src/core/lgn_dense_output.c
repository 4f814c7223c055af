/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Output between steps: q, v and vdot at any t of the last step
 * [t_n, t_{n+1}], from a cubic Hermite interpolant in the chart of the step,
 *
 *   q(t_n + theta h) = q_n o exp(s(theta)),
 *   s(theta) = (theta^3 - 2 theta^2 + theta) h v_n + (3 theta^2 - 2 theta^3) s_1
 *            + (theta^3 - theta^2) h T(s_1)^{-1} v_{n+1},
 *
 * where s_1 = log(q_n^{-1} q_{n+1}) is the step's increment. It matches
 * q and v at both ends (T(0) = I), so the output is continuous in q and v
 * across steps; its error is O(h^4) locally, below the method's O(h^3):
 * the interpolated solution keeps the order of the method. v and vdot come
 * from its derivatives, with v = T(s) s' / h and
 * vdot = Tdot(s, s'/h) s'/h + T(s) s'' / h^2 (vdot is first order).
 * The BDF family interpolates with its own polynomials instead, of the
 * order of its last step (BDFDenseOutput).
 * ---------------------------------------------------------------------------*/

#include <string.h>

#include "lgn_impl.h"
#include "lgn_methods.h"

/* The BDF family: the interpolating polynomials of the last step's order
 * k through the newest k + 1 points, x in the chart of the step's start
 * (x_{n+1} = sigma, x_n = 0, x_{n-j} = log(q_n^{-1} q_{n-j})) and v:
 *   q(t) = q_n o exp(P_x(t)),  v(t) = P_v(t),  vdot(t) = P_v'(t),
 * of the method's order (doc/theory.md §8). */
static int BDFDenseOutput(LGNMem mem, sunrealtype t, int k, sunrealtype *out)
{
  LGNGroup G = mem->G;
  const sunindextype nv = mem->nv;
  const int kk = SUNMIN(mem->bdf_last_order, mem->bdf_nhist - 1);
  sunrealtype tau[LGN_BDF_MAXHIST], l[LGN_BDF_MAXHIST], dl[LGN_BDF_MAXHIST];
  sunrealtype *x = mem->dense_work;
  sunindextype i;
  int j, ret;

  tau[0] = mem->tn;
  for (j = 1; j <= kk; j++) tau[j] = mem->bdf_t[j];
  lgnLagrangeBasis(tau, kk, t, l, dl);
  if (k == 0) {
    for (i = 0; i < nv; i++) {
      sunrealtype s = l[0] * mem->sigma[i];
      for (j = 2; j <= kk; j++) s += l[j] * mem->bdf_x[(j - 1) * nv + i];
      x[i] = s; /* (x_n = 0: the j = 1 term vanishes) */
    }
    ret = G->ops.compose_exp(G, lgnData(mem->q1), x, out);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNGetDky");
    return LGN_SUCCESS;
  }
  for (i = 0; i < nv; i++) {
    sunrealtype s = SUN_RCONST(0.0);
    for (j = 0; j <= kk; j++) s += (k == 1 ? l[j] : dl[j]) * mem->bdf_v[j * nv + i];
    out[i] = s;
  }
  return LGN_SUCCESS;
}

/* k = 0: q (nq), 1: v (nv), 2: vdot (nv) at t, tprev <= t <= tn. */
int lgnDenseOutput(LGNMem mem, sunrealtype t, int k, sunrealtype *out)
{
  LGNGroup G = mem->G;
  const sunindextype nv = mem->nv;
  const sunrealtype h = mem->tn - mem->tprev, th = (t - mem->tprev) / h;
  const sunrealtype th2 = th * th, th3 = th2 * th;
  const sunrealtype *s1 = mem->kin->increment(mem);
  const sunrealtype *v0 = lgnData(mem->v1); /* the step's start, kept there */
  sunrealtype *m1 = mem->dense_work, *s = m1 + nv, *sp = s + nv, *spp = sp + nv;
  sunindextype i;
  int ret;

  /* the ends: the step's own values */
  if (t == mem->tn || t == mem->tprev) {
    const sunbooleantype end = t == mem->tn;
    N_Vector x = k == 0 ? (end ? mem->q : mem->q1)
               : k == 1 ? (end ? mem->v : mem->v1)
                        : (end ? mem->vdot : mem->vdot1);
    memcpy(out, lgnData(x), (size_t)(k == 0 ? mem->nq : nv) * sizeof(sunrealtype));
    return LGN_SUCCESS;
  }
  if (mem->family == LGN_FAMILY_BDF && mem->bdf_nhist >= 2) return BDFDenseOutput(mem, t, k, out);
  /* m1 = h T(s_1)^{-1} v_{n+1} */
  ret = G->ops.tangent_inverse_apply(G, s1, lgnData(mem->v), m1);
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNGetDky");
  for (i = 0; i < nv; i++) {
    const sunrealtype m0 = h * v0[i], mh = h * m1[i];
    s[i]   = (th3 - 2 * th2 + th) * m0 + (3 * th2 - 2 * th3) * s1[i] + (th3 - th2) * mh;
    sp[i]  = ((3 * th2 - 4 * th + 1) * m0 + (6 * th - 6 * th2) * s1[i] +
              (3 * th2 - 2 * th) * mh) / h;
    spp[i] = ((6 * th - 4) * m0 + (6 - 12 * th) * s1[i] + (6 * th - 2) * mh) / (h * h);
  }
  if (k == 0) {
    ret = G->ops.compose_exp(G, lgnData(mem->q1), s, out);
  } else if (k == 1) {
    ret = G->ops.tangent_apply(G, s, sp, out);
  } else {
    ret = G->ops.tangent_apply(G, s, spp, out);
    if (ret == 0) ret = G->ops.tangent_dot_apply(G, s, sp, sp, m1);
    for (i = 0; i < nv && ret == 0; i++) out[i] += m1[i];
  }
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNGetDky");
  return LGN_SUCCESS;
}
