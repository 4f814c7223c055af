/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Settings that belong to one method family only. The family is always
 * known (the Newmark family by default; LGNSetBDF selects BDF, LGNSetNewmark,
 * LGNSetGenAlpha and LGNSetGenAlphaParams the Newmark family again), so
 *
 *   - a setter of one family given a value other than its default is
 *     refused while the other family is selected (LGN_ILL_INPUT, the
 *     message names the setter and the family; the default, which asks
 *     nothing of the other family, is accepted), and
 *   - a setting accepted under one family that is not at its default when
 *     the run starts under the other family makes LGNSolve and LGNCalcIC
 *     refuse (LGN_ILL_INPUT naming the setting), so the result does not
 *     depend on the order of the calls: the combination is refused either
 *     way, as IDA refuses inconsistent inputs when the solve starts.
 *
 * Newmark family only: LGNSetKinematics, LGNSetPredictor. BDF only:
 * LGNSetBDFForm. Switching the family itself is always accepted.
 * ---------------------------------------------------------------------------*/

#include "lgn_impl.h"

static const char *FamilyName(int family)
{
  return family == LGN_FAMILY_BDF ? "the BDF family (LGNSetBDF)"
                                  : "the Newmark family (LGNSetNewmark, LGNSetGenAlpha, "
                                    "LGNSetGenAlphaParams)";
}

int lgnRefuseOtherFamily(LGNMem mem, int family, sunbooleantype is_default, const char *func)
{
  if (mem->family == family || is_default) return LGN_SUCCESS;
  lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                  "%s: a value other than the default applies to %s only; %s is "
                  "selected: the setting is refused (nothing changed).", func, FamilyName(family), FamilyName(mem->family));
  return LGN_ILL_INPUT;
}

/* A setting of the other family left at a value other than its default. */
static int Conflict(LGNMem mem, const char *setter, int family, const char *func)
{
  lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                  "%s was given a value other than its default, but it applies to %s "
                  "only and %s is selected: set it back to its default or select "
                  "its family.", setter, FamilyName(family), FamilyName(mem->family));
  return LGN_ILL_INPUT;
}

int lgnCheckFamilySettings(LGNMem mem, const char *func)
{
  if (mem->family == LGN_FAMILY_BDF) {
    if (mem->kinematics != LGN_KINEMATICS_SIMPLIFIED)
      return Conflict(mem, "LGNSetKinematics", LGN_FAMILY_NEWMARK, func);
    if (mem->predictor != LGN_PREDICTOR_ZERO)
      return Conflict(mem, "LGNSetPredictor", LGN_FAMILY_NEWMARK, func);
  } else if (mem->bdf_form != LGN_BDF_VARIABLE_COEFF) {
    return Conflict(mem, "LGNSetBDFForm", LGN_FAMILY_BDF, func);
  }
  return LGN_SUCCESS;
}
