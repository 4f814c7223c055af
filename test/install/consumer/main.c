/* -----------------------------------------------------------------------------
 * Lignum install test: a program outside the source tree that uses the
 * installed headers and library (via find_package(Lignum) or lignum.pc).
 * Exits nonzero on any mismatch.
 * ---------------------------------------------------------------------------*/

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static int nfail = 0;

static void check(int ok, const char *what)
{
  if (!ok) {
    fprintf(stderr, "FAILED: %s\n", what);
    nfail++;
  }
}

static int close_to(sunrealtype x, sunrealtype ref)
{
  return fabs(x - ref) <= SUN_RCONST(1e-14) * (SUN_RCONST(1.0) + fabs(ref));
}

int main(void)
{
  SUNContext ctx = NULL;
  LGNGroup G = NULL;
  void *mem = NULL;
  sunrealtype am = 0, af = 0, beta = 0, gamma = 0;
  const char *name = NULL;

  printf("Lignum %s (%d.%d.%d)\n", LGN_VERSION, LGN_VERSION_MAJOR,
         LGN_VERSION_MINOR, LGN_VERSION_PATCH);
#ifdef LIGNUM_EXPECTED_VERSION
  check(strcmp(LGN_VERSION, LIGNUM_EXPECTED_VERSION) == 0,
        "LGN_VERSION equals the version of the package found");
#endif

  if (SUNContext_Create(NULL, &ctx) != 0 || ctx == NULL) {
    fprintf(stderr, "FAILED: SUNContext_Create\n");
    return 1;
  }

  /* R^3 x SO(3): q = (x, quaternion), nq = 7, nv = 6 */
  G = LGNGroup_R3xSO3();
  check(G != NULL, "LGNGroup_R3xSO3 returns a group");
  if (G != NULL) {
    check(G->nq == 7 && G->nv == 6, "R3xSO3 has nq = 7, nv = 6");
  }

  /* Chung-Hulbert parameters for rho_inf = 0.9:
   * alpha_m = 8/19 = 0.421053.., alpha_f = 9/19, gamma = 21/38, beta = 100/361 */
  check(LGNGenAlphaFromRhoInf(SUN_RCONST(0.9), &am, &af, &beta, &gamma) ==
          LGN_SUCCESS,
        "LGNGenAlphaFromRhoInf(0.9) returns LGN_SUCCESS");
  printf("rho_inf = 0.9: alpha_m = %.6f, alpha_f = %.6f, beta = %.6f, "
         "gamma = %.6f\n", (double)am, (double)af, (double)beta, (double)gamma);
  check(close_to(am, SUN_RCONST(8.0) / SUN_RCONST(19.0)), "alpha_m = 8/19");
  check(close_to(af, SUN_RCONST(9.0) / SUN_RCONST(19.0)), "alpha_f = 9/19");
  check(close_to(gamma, SUN_RCONST(21.0) / SUN_RCONST(38.0)), "gamma = 21/38");
  check(close_to(beta, SUN_RCONST(100.0) / SUN_RCONST(361.0)), "beta = 100/361");

  /* Lifecycle */
  mem = LGNCreate(ctx);
  check(mem != NULL, "LGNCreate returns a memory block");
  LGNFree(&mem);
  check(mem == NULL, "LGNFree sets the pointer to NULL");

  /* Return flag names */
  name = LGNGetReturnFlagName(LGN_CONV_FAILURE);
  check(name != NULL && strcmp(name, "LGN_CONV_FAILURE") == 0,
        "LGNGetReturnFlagName(LGN_CONV_FAILURE) is \"LGN_CONV_FAILURE\"");

  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);

  if (nfail > 0) {
    fprintf(stderr, "%d check(s) failed\n", nfail);
    return 1;
  }
  printf("install test: all checks passed\n");
  return 0;
}
