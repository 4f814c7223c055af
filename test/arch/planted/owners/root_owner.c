/* Planted for arch_check_owners_rejects: the owner of rt and ec writes
 * them (accepted); comments and strings that look like writes are not. */
void plantRootOwner(struct LGNMemRec *mem)
{
  mem->rt.nge++;
  mem->ec.hnext = 0.5; /* mem->bdf.order = 2 in a comment is no write */
  report("mem->bdf.order = 3");
}
