/* -----------------------------------------------------------------------------
 * Found by test/fuzz (lgn_fuzz, UBSan), minimised by hand. Not part of the
 * suite.
 *
 * LGNSetConstraints accepts any m >= 0, e.g. m = 2^40 (it cannot know the
 * model; LGNInit and LGNSolve later fail on it, or run out of memory), and
 * LGNGetIterationMatrixNnz then computes (nv + m)^2 in long int
 * (lgnIterationMatrixNnz, src/core/lgn_mem.c: `return n * n;`): signed overflow,
 * undefined behaviour, reported by -fsanitize=undefined as
 *   src/core/lgn_mem.c:560:12: runtime error: signed integer overflow:
 *   1099511627776 * 1099511627776 cannot be represented in type 'long'
 * (nv = 0 before LGNInit; any nv + m > 3.04e9 overflows). Without a sanitizer the
 * getter returns a wrapped, possibly negative count. Either refuse such m
 * in LGNSetConstraints (e.g. (nv + m)^2 must fit a long int / sunindextype)
 * or saturate / report in the getter.
 *
 *   clang -fsanitize=undefined -fno-sanitize-recover=all \
 *     iteration_matrix_nnz_overflow.c -I<lignum>/include -I<build>/include \
 *     -L<build>/src -llignum -lsundials_nvecserial -lm && ./a.out
 * stops with the runtime error above (built from the UBSan objects of
 * build-clang-asan/ or build-fuzz/ it names src/core/lgn_mem.c).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>
#include <nvector/nvector_serial.h>

static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  (void)t; (void)q; (void)phi; (void)ud;
  return 0;
}

static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)t; (void)q; (void)B; (void)ud;
  return 0;
}

int main(void)
{
  SUNContext ctx;
  LGNGroup G;
  void *mem;
  long int nnz = 0;
  int flag;
  SUNContext_Create(NULL, &ctx);
  G   = LGNGroup_Rn(1);
  mem = LGNCreate(ctx);
  LGNSetGroup(mem, G);
  flag = LGNSetConstraints(mem, (sunindextype)1 << 40, Phi, Jac);
  printf("LGNSetConstraints(m = 2^40) -> %s\n", LGNGetReturnFlagName(flag));
  flag = LGNGetIterationMatrixNnz(mem, &nnz); /* UB: (1 + 2^40)^2 */
  printf("LGNGetIterationMatrixNnz -> %s, nnz = %ld\n", LGNGetReturnFlagName(flag), nnz);
  LGNFree(&mem);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return 0;
}
