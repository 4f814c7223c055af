/* Method parameters: the Chung-Hulbert map rho_inf -> (alpha_m, alpha_f,
 * gamma, beta) against the table of doc/theory.md §2, the second-order
 * condition, and rejection of illegal values. */
#include <lignum/lignum.h>
#include <sundials/sundials_context.h>

#include "test_util.h"

static void Silent(int code, const char *mod, const char *fn, const char *msg, void *d)
{
  (void)code; (void)mod; (void)fn; (void)msg; (void)d;
}

int main(void)
{
  /* spec table (6 printed digits) */
  const double rho[4]  = {1.0, 0.9, 0.8, 0.6};
  const double am[4]   = {0.5, 0.421053, 0.333333, 0.125};
  const double af[4]   = {0.5, 0.473684, 0.444444, 0.375};
  const double gam[4]  = {0.5, 0.552632, 0.611111, 0.75};
  const double bet[4]  = {0.25, 0.277008, 0.308642, 0.390625};
  sunrealtype a_m, a_f, b, g;
  SUNContext ctx;
  void *mem;
  int i, flag;

  for (i = 0; i < 4; i++) {
    flag = LGNGenAlphaFromRhoInf(rho[i], &a_m, &a_f, &b, &g);
    CHECK(flag == LGN_SUCCESS, "rho_inf = %g accepted", rho[i]);
    CHECK_CLOSE(a_m, am[i], 5e-7, "alpha_m");
    CHECK_CLOSE(a_f, af[i], 5e-7, "alpha_f");
    CHECK_CLOSE(g, gam[i], 5e-7, "gamma");
    CHECK_CLOSE(b, bet[i], 5e-7, "beta");
    /* second order: gamma = 1/2 - alpha_m + alpha_f */
    CHECK_CLOSE(g, 0.5 - a_m + a_f, 1e-15, "gamma - (1/2 - am + af)");
    /* unconditional stability: am <= af <= 1/2, beta >= 1/4 + (af - am)/2 */
    CHECK(a_m <= a_f && a_f <= 0.5 && b >= 0.25 + 0.5 * (a_f - a_m) - 1e-15,
          "stability conditions at rho_inf = %g", rho[i]);
    /* PETSc's TSALPHA2 convention weights the new value: alpha_f(PETSc) =
     * 1/(1+rho) = 1 - alpha_f(Chung-Hulbert) */
    CHECK_CLOSE(1.0 - a_f, 1.0 / (1.0 + rho[i]), 1e-15, "1 - alpha_f = 1/(1+rho)");
  }
  /* rho_inf = 0 */
  flag = LGNGenAlphaFromRhoInf(0.0, &a_m, &a_f, &b, &g);
  CHECK(flag == LGN_SUCCESS && a_m == -1.0 && a_f == 0.0 && g == 1.5 && b == 1.0,
        "rho_inf = 0 gives (-1, 0, 1, 1.5)");

  /* illegal values (messages go to stderr: that is the default handler) */
  CHECK(LGNGenAlphaFromRhoInf(1.0001, &a_m, &a_f, &b, &g) == LGN_ILL_INPUT, "rho 1.0001 rejected");
  CHECK(LGNGenAlphaFromRhoInf(-0.1, &a_m, &a_f, &b, &g) == LGN_ILL_INPUT, "rho -0.1 rejected");
  CHECK(LGNGenAlphaFromRhoInf(NAN, &a_m, &a_f, &b, &g) == LGN_ILL_INPUT, "rho NaN rejected");
  CHECK(LGNGenAlphaFromRhoInf(0.5, NULL, &a_f, &b, &g) == LGN_ILL_INPUT, "NULL output rejected");

  /* through the memory block */
  SUNContext_Create(NULL, &ctx);
  mem = LGNCreate(ctx);
  LGNSetErrHandlerFn(mem, Silent, NULL);
  LGNGetMethodParams(mem, &a_m, &a_f, &b, &g);
  CHECK_CLOSE(a_m, 8.0 / 19.0, 1e-15, "default alpha_m (rho_inf 0.9)");
  CHECK(LGNSetGenAlpha(mem, 0.6) == LGN_SUCCESS, "LGNSetGenAlpha(0.6)");
  LGNGetMethodParams(mem, &a_m, &a_f, &b, &g);
  CHECK_CLOSE(b, 0.390625, 1e-15, "beta after LGNSetGenAlpha(0.6)");
  CHECK(LGNSetGenAlpha(mem, 1.5) == LGN_ILL_INPUT, "LGNSetGenAlpha(1.5) rejected");
  LGNGetMethodParams(mem, &a_m, &a_f, &b, &g);
  CHECK_CLOSE(b, 0.390625, 1e-15, "parameters unchanged after a rejected call");
  CHECK(LGNSetNewmark(mem, 0.25, 0.5) == LGN_SUCCESS, "Newmark(1/4, 1/2)");
  LGNGetMethodParams(mem, &a_m, &a_f, &b, &g);
  CHECK(a_m == 0.0 && a_f == 0.0 && b == 0.25 && g == 0.5, "Newmark sets alpha_m = alpha_f = 0");
  CHECK(LGNSetNewmark(mem, 0.0, 0.5) == LGN_ILL_INPUT, "Newmark beta = 0 rejected");
  CHECK(LGNSetNewmark(mem, 0.25, 1.2) == LGN_ILL_INPUT, "Newmark gamma = 1.2 rejected");
  CHECK(LGNSetGenAlphaParams(mem, 1.0, 0.5, 0.3, 0.6) == LGN_ILL_INPUT, "alpha_m = 1 rejected");
  CHECK(LGNSetGenAlphaParams(mem, 0.2, 0.4, 0.3, 0.7) == LGN_SUCCESS, "four parameters accepted");
  LGNFree(&mem);
  CHECK(mem == NULL, "LGNFree sets the pointer to NULL");
  SUNContext_Free(&ctx);
  return test_summary("test_params");
}
