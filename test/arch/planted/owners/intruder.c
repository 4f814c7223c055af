/* Planted for arch_check_owners_rejects: writes of sub-records this file
 * does not own, one of each kind the check must see. */
void plantIntruder(struct LGNMemRec *mem, double h)
{
  mem->ec.hnext = h;          /* an assignment            */
  ++mem->rt.nge;              /* a prefix increment       */
  mem->rt.glo[0] += h;        /* a compound assignment to an element */
  if (mem->ec.hnext == h) {   /* a comparison: no write   */
    h = mem->rt.tlo;          /* a read: no write         */
  }
}
