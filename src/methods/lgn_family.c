/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The method families, one table of operations each (LGNFamilyOps,
 * lgn_impl.h): the Newmark / generalized-alpha family (lgn_newmark_step.c,
 * lgn_newmark_adapt.c, lgn_newmark_errtest.c, the Hermite output of lgn_dense_output.c) and the
 * BDF family (lgn_bdf.c and its interpolating polynomials in lgn_dense_output.c).
 * The driver (lgn.c), the getters (lgn_setget.c), the dense output, the error
 * norm and Newton reach the family only through mem->fam; adding a family
 * is adding its files and one table here.
 * ---------------------------------------------------------------------------*/

#include "lgn_impl.h"

/* The order the Newmark family reports: 2 for the next and the last step. */
static int NewmarkOrder(const struct LGNMemRec *mem, sunbooleantype last)
{
  (void)mem;
  (void)last;
  return 2;
}

static int BDFOrder(const struct LGNMemRec *mem, sunbooleantype last)
{
  return last ? mem->bdf.last_order : mem->bdf.order;
}

static const LGNFamilyOps NewmarkFamily = {
  "Newmark / generalized-alpha",
  LGN_FAMILY_NEWMARK,
  SUNFALSE,             /* error per unit step (lgnErrorNorm)               */
  SUNFALSE,             /* a fixed step is shortened to arrive at tout      */
  SUNTRUE,              /* GGL corrects with B(q_n) (lgn_kinematics.c)      */
  NULL,                 /* no work space of its own beyond lgnAllocWork     */
  lgnStep,
  lgnAdaptiveStep,
  NULL,                 /* the cubic Hermite interpolant of lgn_dense_output.c     */
  NewmarkOrder,
};

static const LGNFamilyOps BDFFamily = {
  "BDF",
  LGN_FAMILY_BDF,
  SUNTRUE,              /* error in the units of the step                   */
  SUNTRUE,              /* keeps its grid: steps past tout, interpolates    */
  SUNFALSE,             /* GGL at the iterate (B(q1), no B(q_n))            */
  lgnAllocBDF,
  lgnBDFStep,
  lgnBDFAdaptiveStep,
  lgnBDFDenseOutput,
  BDFOrder,
};

const LGNFamilyOps *lgnFamilyOps(int family)
{
  return family == LGN_FAMILY_BDF ? &BDFFamily : &NewmarkFamily;
}
