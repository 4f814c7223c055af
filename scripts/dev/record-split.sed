# scripts/dev/record-split.sed: ports code written against the flat
# integrator record (before issue 32) to the record split by owner:
#   sed -E -i -f scripts/dev/record-split.sed FILE.c ...
# rewrites mem->field to mem->sub.field (also (*mem)->field and
# ((LGNMem)x)->field; another name of the record is left alone), and the
# restart tables' SCALAR/ARRAY/INLINE(field, ...) entries of moved fields
# (the file keeps the old name). GNU sed, -E; apply once.
# Not rewritten (port by hand; the compiler names each): the record under
# another name (FlattenGroup's `out`, a test's `m`), and a macro that pastes a
# field name after mem-> (KRYLOV_GETTER in lgn_krylov.c now writes
# mem->kry.FIELD). New fields of a sub-record go into its struct in
# lgn_impl.h, and a new writer of one into doc/architecture.md's owners
# table (the test arch_check_owners).
# ---- ranks: struct LGNRanksRec (a run across MPI ranks and its ghost bodies)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->par\b/\1->ranks.par/g
s/\b(SCALAR|ARRAY|INLINE)\(par,/\1N(par, ranks.par,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nv_all\b/\1->ranks.nv_all/g
s/\b(SCALAR|ARRAY|INLINE)\(nv_all,/\1N(nv_all, ranks.nv_all,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->m_all\b/\1->ranks.m_all/g
s/\b(SCALAR|ARRAY|INLINE)\(m_all,/\1N(m_all, ranks.m_all,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->any_constr_time\b/\1->ranks.any_constr_time/g
s/\b(SCALAR|ARRAY|INLINE)\(any_constr_time,/\1N(any_constr_time, ranks.any_constr_time,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->halo\b/\1->ranks.halo/g
s/\b(SCALAR|ARRAY|INLINE)\(halo,/\1N(halo, ranks.halo,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nv_own\b/\1->ranks.nv_own/g
s/\b(SCALAR|ARRAY|INLINE)\(nv_own,/\1N(nv_own, ranks.nv_own,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nq_own\b/\1->ranks.nq_own/g
s/\b(SCALAR|ARRAY|INLINE)\(nq_own,/\1N(nq_own, ranks.nq_own,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->hx_b\b/\1->ranks.hx_b/g
s/\b(SCALAR|ARRAY|INLINE)\(hx_b,/\1N(hx_b, ranks.hx_b,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->hx_x\b/\1->ranks.hx_x/g
s/\b(SCALAR|ARRAY|INLINE)\(hx_x,/\1N(hx_x, ranks.hx_x,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->hx_ext\b/\1->ranks.hx_ext/g
s/\b(SCALAR|ARRAY|INLINE)\(hx_ext,/\1N(hx_ext, ranks.hx_ext,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->hx_ext2\b/\1->ranks.hx_ext2/g
s/\b(SCALAR|ARRAY|INLINE)\(hx_ext2,/\1N(hx_ext2, ranks.hx_ext2,/g
# ---- bdf: struct LGNBDFRec (the BDF family: settings, history q_{n-j}, v_{n-j} at t_{n-j}, order control)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_maxord\b/\1->bdf.maxord/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_maxord,/\1N(bdf_maxord, bdf.maxord,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_form\b/\1->bdf.form/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_form,/\1N(bdf_form, bdf.form,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_ns\b/\1->bdf.ns/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_ns,/\1N(bdf_ns, bdf.ns,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_hused\b/\1->bdf.hused/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_hused,/\1N(bdf_hused, bdf.hused,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_sigck\b/\1->bdf.sigck/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_sigck,/\1N(bdf_sigck, bdf.sigck,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_step_flc\b/\1->bdf.step_flc/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_step_flc,/\1N(bdf_step_flc, bdf.step_flc,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_order\b/\1->bdf.order/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_order,/\1N(bdf_order, bdf.order,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_last_order\b/\1->bdf.last_order/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_last_order,/\1N(bdf_last_order, bdf.last_order,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_nhist\b/\1->bdf.nhist/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_nhist,/\1N(bdf_nhist, bdf.nhist,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_nsteps_order\b/\1->bdf.nsteps_order/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_nsteps_order,/\1N(bdf_nsteps_order, bdf.nsteps_order,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_phase0\b/\1->bdf.phase0/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_phase0,/\1N(bdf_phase0, bdf.phase0,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_chart_t\b/\1->bdf.chart_t/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_chart_t,/\1N(bdf_chart_t, bdf.chart_t,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_t\b/\1->bdf.t/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_t,/\1N(bdf_t, bdf.t,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_vgain\b/\1->bdf.vgain/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_vgain,/\1N(bdf_vgain, bdf.vgain,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_vgain1\b/\1->bdf.vgain1/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_vgain1,/\1N(bdf_vgain1, bdf.vgain1,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_vpgain\b/\1->bdf.vpgain/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_vpgain,/\1N(bdf_vpgain, bdf.vpgain,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_q\b/\1->bdf.q/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_q,/\1N(bdf_q, bdf.q,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_v\b/\1->bdf.v/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_v,/\1N(bdf_v, bdf.v,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_l\b/\1->bdf.l/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_l,/\1N(bdf_l, bdf.l,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_x\b/\1->bdf.x/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_x,/\1N(bdf_x, bdf.x,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_rx\b/\1->bdf.rx/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_rx,/\1N(bdf_rx, bdf.rx,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_rv\b/\1->bdf.rv/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_rv,/\1N(bdf_rv, bdf.rv,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_xpred\b/\1->bdf.xpred/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_xpred,/\1N(bdf_xpred, bdf.xpred,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_vpred\b/\1->bdf.vpred/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_vpred,/\1N(bdf_vpred, bdf.vpred,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_dd\b/\1->bdf.dd/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_dd,/\1N(bdf_dd, bdf.dd,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_ele_keep\b/\1->bdf.ele_keep/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_ele_keep,/\1N(bdf_ele_keep, bdf.ele_keep,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_c0\b/\1->bdf.c0/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_c0,/\1N(bdf_c0, bdf.c0,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bdf_nord\b/\1->bdf.nord/g
s/\b(SCALAR|ARRAY|INLINE)\(bdf_nord,/\1N(bdf_nord, bdf.nord,/g
# ---- blk: struct LGNBlocksRec (the diagonal blocks of T: the leaves of the group)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nblk\b/\1->blk.n/g
s/\b(SCALAR|ARRAY|INLINE)\(nblk,/\1N(nblk, blk.n,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->blk_voff\b/\1->blk.voff/g
s/\b(SCALAR|ARRAY|INLINE)\(blk_voff,/\1N(blk_voff, blk.voff,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->blk_qoff\b/\1->blk.qoff/g
s/\b(SCALAR|ARRAY|INLINE)\(blk_qoff,/\1N(blk_qoff, blk.qoff,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->blk_toff\b/\1->blk.toff/g
s/\b(SCALAR|ARRAY|INLINE)\(blk_toff,/\1N(blk_toff, blk.toff,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->blk_of\b/\1->blk.of/g
s/\b(SCALAR|ARRAY|INLINE)\(blk_of,/\1N(blk_of, blk.of,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->blk_group\b/\1->blk.group/g
s/\b(SCALAR|ARRAY|INLINE)\(blk_group,/\1N(blk_group, blk.group,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->blk_max\b/\1->blk.max/g
s/\b(SCALAR|ARRAY|INLINE)\(blk_max,/\1N(blk_max, blk.max,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->tlen\b/\1->blk.tlen/g
s/\b(SCALAR|ARRAY|INLINE)\(tlen,/\1N(tlen, blk.tlen,/g
# ---- dq: struct LGNDQRec (difference-quotient scratch vectors)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->dq_q\b/\1->dq.q/g
s/\b(SCALAR|ARRAY|INLINE)\(dq_q,/\1N(dq_q, dq.q,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->dq_v\b/\1->dq.v/g
s/\b(SCALAR|ARRAY|INLINE)\(dq_v,/\1N(dq_v, dq.v,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->dq_g\b/\1->dq.g/g
s/\b(SCALAR|ARRAY|INLINE)\(dq_g,/\1N(dq_g, dq.g,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->dq_r\b/\1->dq.r/g
s/\b(SCALAR|ARRAY|INLINE)\(dq_r,/\1N(dq_r, dq.r,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->dq_z\b/\1->dq.z/g
s/\b(SCALAR|ARRAY|INLINE)\(dq_z,/\1N(dq_z, dq.z,/g
# ---- ls: struct LGNLinSolRec (the linear solver (LS and A not owned))
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->LS\b/\1->ls.LS/g
s/\b(SCALAR|ARRAY|INLINE)\(LS,/\1N(LS, ls.LS,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->A\b/\1->ls.A/g
s/\b(SCALAR|ARRAY|INLINE)\(A,/\1N(A, ls.A,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->sparse\b/\1->ls.sparse/g
s/\b(SCALAR|ARRAY|INLINE)\(sparse,/\1N(sparse, ls.sparse,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->sparsetype\b/\1->ls.sparsetype/g
s/\b(SCALAR|ARRAY|INLINE)\(sparsetype,/\1N(sparsetype, ls.sparsetype,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->sp\b/\1->ls.sp/g
s/\b(SCALAR|ARRAY|INLINE)\(sp,/\1N(sp, ls.sp,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->ls_initialized\b/\1->ls.initialized/g
s/\b(SCALAR|ARRAY|INLINE)\(ls_initialized,/\1N(ls_initialized, ls.initialized,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->ls_restart\b/\1->ls.restart/g
s/\b(SCALAR|ARRAY|INLINE)\(ls_restart,/\1N(ls_restart, ls.restart,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lsetup_recoverable\b/\1->ls.setup_recoverable/g
s/\b(SCALAR|ARRAY|INLINE)\(lsetup_recoverable,/\1N(lsetup_recoverable, ls.setup_recoverable,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->last_lin_flag\b/\1->ls.last_flag/g
s/\b(SCALAR|ARRAY|INLINE)\(last_lin_flag,/\1N(last_lin_flag, ls.last_flag,/g
# ---- kry: struct LGNKrylovRec (Krylov solvers and preconditioners)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->krylov\b/\1->kry.on/g
s/\b(SCALAR|ARRAY|INLINE)\(krylov,/\1N(krylov, kry.on,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->own_A\b/\1->kry.own_A/g
s/\b(SCALAR|ARRAY|INLINE)\(own_A,/\1N(own_A, kry.own_A,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->kry_pretype\b/\1->kry.pretype/g
s/\b(SCALAR|ARRAY|INLINE)\(kry_pretype,/\1N(kry_pretype, kry.pretype,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->psetup\b/\1->kry.psetup/g
s/\b(SCALAR|ARRAY|INLINE)\(psetup,/\1N(psetup, kry.psetup,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->psolve\b/\1->kry.psolve/g
s/\b(SCALAR|ARRAY|INLINE)\(psolve,/\1N(psolve, kry.psolve,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bp_nblocks\b/\1->kry.bp_nblocks/g
s/\b(SCALAR|ARRAY|INLINE)\(bp_nblocks,/\1N(bp_nblocks, kry.bp_nblocks,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bp_bodies\b/\1->kry.bp_bodies/g
s/\b(SCALAR|ARRAY|INLINE)\(bp_bodies,/\1N(bp_bodies, kry.bp_bodies,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->bp\b/\1->kry.bp/g
s/\b(SCALAR|ARRAY|INLINE)\(bp,/\1N(bp, kry.bp,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->kry_w\b/\1->kry.w/g
s/\b(SCALAR|ARRAY|INLINE)\(kry_w,/\1N(kry_w, kry.w,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->kry_tmp\b/\1->kry.tmp/g
s/\b(SCALAR|ARRAY|INLINE)\(kry_tmp,/\1N(kry_tmp, kry.tmp,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->eplifac\b/\1->kry.eplifac/g
s/\b(SCALAR|ARRAY|INLINE)\(eplifac,/\1N(eplifac, kry.eplifac,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->kry_newton\b/\1->kry.newton/g
s/\b(SCALAR|ARRAY|INLINE)\(kry_newton,/\1N(kry_newton, kry.newton,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->asm_t\b/\1->kry.asm_t/g
s/\b(SCALAR|ARRAY|INLINE)\(asm_t,/\1N(asm_t, kry.asm_t,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->asm_cM\b/\1->kry.asm_cM/g
s/\b(SCALAR|ARRAY|INLINE)\(asm_cM,/\1N(asm_cM, kry.asm_cM,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->asm_cC\b/\1->kry.asm_cC/g
s/\b(SCALAR|ARRAY|INLINE)\(asm_cC,/\1N(asm_cC, kry.asm_cC,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->asm_cK\b/\1->kry.asm_cK/g
s/\b(SCALAR|ARRAY|INLINE)\(asm_cK,/\1N(asm_cK, kry.asm_cK,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nli\b/\1->kry.nli/g
s/\b(SCALAR|ARRAY|INLINE)\(nli,/\1N(nli, kry.nli,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->npe\b/\1->kry.npe/g
s/\b(SCALAR|ARRAY|INLINE)\(npe,/\1N(npe, kry.npe,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nps\b/\1->kry.nps/g
s/\b(SCALAR|ARRAY|INLINE)\(nps,/\1N(nps, kry.nps,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->njtimes\b/\1->kry.njtimes/g
s/\b(SCALAR|ARRAY|INLINE)\(njtimes,/\1N(njtimes, kry.njtimes,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nlcf\b/\1->kry.nlcf/g
s/\b(SCALAR|ARRAY|INLINE)\(nlcf,/\1N(nlcf, kry.nlcf,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->kry_pfail\b/\1->kry.pfail/g
s/\b(SCALAR|ARRAY|INLINE)\(kry_pfail,/\1N(kry_pfail, kry.pfail,/g
# ---- klu: struct LGNKluRec (Lignum's solves with a copy of KLU's factors)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->own_klu_solves\b/\1->klu.own_solves/g
s/\b(SCALAR|ARRAY|INLINE)\(own_klu_solves,/\1N(own_klu_solves, klu.own_solves,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->klu_valid\b/\1->klu.valid/g
s/\b(SCALAR|ARRAY|INLINE)\(klu_valid,/\1N(klu_valid, klu.valid,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->klu_nsolve\b/\1->klu.ls_nsolve/g
s/\b(SCALAR|ARRAY|INLINE)\(klu_nsolve,/\1N(klu_nsolve, klu.ls_nsolve,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->klu\b([^.]|$)/\1->klu.copy\3/g
s/\b(SCALAR|ARRAY|INLINE)\(klu,/\1N(klu, klu.copy,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->klu_pattern\b/\1->klu.pattern/g
s/\b(SCALAR|ARRAY|INLINE)\(klu_pattern,/\1N(klu_pattern, klu.pattern,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nklu_fallback\b/\1->klu.nfallback/g
s/\b(SCALAR|ARRAY|INLINE)\(nklu_fallback,/\1N(nklu_fallback, klu.nfallback,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nklu_copy\b/\1->klu.ncopy/g
s/\b(SCALAR|ARRAY|INLINE)\(nklu_copy,/\1N(nklu_copy, klu.ncopy,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nklu_values\b/\1->klu.nvalues/g
s/\b(SCALAR|ARRAY|INLINE)\(nklu_values,/\1N(nklu_values, klu.nvalues,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nklu_refactor\b/\1->klu.nrefactor/g
s/\b(SCALAR|ARRAY|INLINE)\(nklu_refactor,/\1N(nklu_refactor, klu.nrefactor,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nklu_solve\b/\1->klu.nsolve/g
s/\b(SCALAR|ARRAY|INLINE)\(nklu_solve,/\1N(nklu_solve, klu.nsolve,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nklu_newpattern\b/\1->klu.nnewpattern/g
s/\b(SCALAR|ARRAY|INLINE)\(nklu_newpattern,/\1N(nklu_newpattern, klu.nnewpattern,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nklu_nocopy\b/\1->klu.nnocopy/g
s/\b(SCALAR|ARRAY|INLINE)\(nklu_nocopy,/\1N(nklu_nocopy, klu.nnocopy,/g
# ---- red: struct LGNRedundancyRec (redundant constraints)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->m_user\b/\1->red.m_user/g
s/\b(SCALAR|ARRAY|INLINE)\(m_user,/\1N(m_user, red.m_user,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_mode\b/\1->red.mode/g
s/\b(SCALAR|ARRAY|INLINE)\(red_mode,/\1N(red_mode, red.mode,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_nout\b/\1->red.nout/g
s/\b(SCALAR|ARRAY|INLINE)\(red_nout,/\1N(red_nout, red.nout,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_rows\b/\1->red.rows/g
s/\b(SCALAR|ARRAY|INLINE)\(red_rows,/\1N(red_rows, red.rows,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_keep\b/\1->red.keep/g
s/\b(SCALAR|ARRAY|INLINE)\(red_keep,/\1N(red_keep, red.keep,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_full\b/\1->red.full/g
s/\b(SCALAR|ARRAY|INLINE)\(red_full,/\1N(red_full, red.full,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_lam\b/\1->red.lam/g
s/\b(SCALAR|ARRAY|INLINE)\(red_lam,/\1N(red_lam, red.lam,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_B\b/\1->red.B/g
s/\b(SCALAR|ARRAY|INLINE)\(red_B,/\1N(red_B, red.B,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_viol\b/\1->red.viol/g
s/\b(SCALAR|ARRAY|INLINE)\(red_viol,/\1N(red_viol, red.viol,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_nsel\b/\1->red.nsel/g
s/\b(SCALAR|ARRAY|INLINE)\(red_nsel,/\1N(red_nsel, red.nsel,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_A\b/\1->red.A/g
s/\b(SCALAR|ARRAY|INLINE)\(red_A,/\1N(red_A, red.A,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_LS\b/\1->red.LS/g
s/\b(SCALAR|ARRAY|INLINE)\(red_LS,/\1N(red_LS, red.LS,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_Auser\b/\1->red.Auser/g
s/\b(SCALAR|ARRAY|INLINE)\(red_Auser,/\1N(red_Auser, red.Auser,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->red_LSuser\b/\1->red.LSuser/g
s/\b(SCALAR|ARRAY|INLINE)\(red_LSuser,/\1N(red_LSuser, red.LSuser,/g
# ---- diag: struct LGNDiagRec (the diagnosis of the last singular matrix)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->diag_red\b/\1->diag.red/g
s/\b(SCALAR|ARRAY|INLINE)\(diag_red,/\1N(diag_red, diag.red,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->diag_nred\b/\1->diag.nred/g
s/\b(SCALAR|ARRAY|INLINE)\(diag_nred,/\1N(diag_nred, diag.nred,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->diag_pivot\b/\1->diag.pivot/g
s/\b(SCALAR|ARRAY|INLINE)\(diag_pivot,/\1N(diag_pivot, diag.pivot,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->diag_text\b/\1->diag.text/g
s/\b(SCALAR|ARRAY|INLINE)\(diag_text,/\1N(diag_text, diag.text,/g
# ---- nls: struct LGNNewtonRec (the Newton iteration: tolerances, the reused factorisation)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lu_valid\b/\1->nls.lu_valid/g
s/\b(SCALAR|ARRAY|INLINE)\(lu_valid,/\1N(lu_valid, nls.lu_valid,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lu_h\b/\1->nls.lu_h/g
s/\b(SCALAR|ARRAY|INLINE)\(lu_h,/\1N(lu_h, nls.lu_h,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lu_nst\b/\1->nls.lu_nst/g
s/\b(SCALAR|ARRAY|INLINE)\(lu_nst,/\1N(lu_nst, nls.lu_nst,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->newton_rate\b/\1->nls.rate/g
s/\b(SCALAR|ARRAY|INLINE)\(newton_rate,/\1N(newton_rate, nls.rate,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lambda_noise\b/\1->nls.lambda_noise/g
s/\b(SCALAR|ARRAY|INLINE)\(lambda_noise,/\1N(lambda_noise, nls.lambda_noise,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lambda_noise_h\b/\1->nls.lambda_noise_h/g
s/\b(SCALAR|ARRAY|INLINE)\(lambda_noise_h,/\1N(lambda_noise_h, nls.lambda_noise_h,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nls_rtol\b/\1->nls.rtol/g
s/\b(SCALAR|ARRAY|INLINE)\(nls_rtol,/\1N(nls_rtol, nls.rtol,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nls_atol\b/\1->nls.atol/g
s/\b(SCALAR|ARRAY|INLINE)\(nls_atol,/\1N(nls_atol, nls.atol,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nls_atolv\b/\1->nls.atolv/g
s/\b(SCALAR|ARRAY|INLINE)\(nls_atolv,/\1N(nls_atolv, nls.atolv,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nls_vfac\b/\1->nls.vfac/g
s/\b(SCALAR|ARRAY|INLINE)\(nls_vfac,/\1N(nls_vfac, nls.vfac,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nls_lrtol\b/\1->nls.lrtol/g
s/\b(SCALAR|ARRAY|INLINE)\(nls_lrtol,/\1N(nls_lrtol, nls.lrtol,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nls_latol\b/\1->nls.latol/g
s/\b(SCALAR|ARRAY|INLINE)\(nls_latol,/\1N(nls_latol, nls.latol,/g
# ---- ec: struct LGNErrConRec (error control and step-size selection (LGN_STEP_ADAPTIVE))
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->step_control\b/\1->ec.step_control/g
s/\b(SCALAR|ARRAY|INLINE)\(step_control,/\1N(step_control, ec.step_control,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->tols_set\b/\1->ec.tols_set/g
s/\b(SCALAR|ARRAY|INLINE)\(tols_set,/\1N(tols_set, ec.tols_set,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->atol_vec\b/\1->ec.atol_vec/g
s/\b(SCALAR|ARRAY|INLINE)\(atol_vec,/\1N(atol_vec, ec.atol_vec,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->epcon\b/\1->ec.epcon/g
s/\b(SCALAR|ARRAY|INLINE)\(epcon,/\1N(epcon, ec.epcon,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->h0_user\b/\1->ec.h0_user/g
s/\b(SCALAR|ARRAY|INLINE)\(h0_user,/\1N(h0_user, ec.h0_user,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->hmin\b/\1->ec.hmin/g
s/\b(SCALAR|ARRAY|INLINE)\(hmin,/\1N(hmin, ec.hmin,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->hmax\b/\1->ec.hmax/g
s/\b(SCALAR|ARRAY|INLINE)\(hmax,/\1N(hmax, ec.hmax,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->maxnef\b/\1->ec.maxnef/g
s/\b(SCALAR|ARRAY|INLINE)\(maxnef,/\1N(maxnef, ec.maxnef,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->maxncf\b/\1->ec.maxncf/g
s/\b(SCALAR|ARRAY|INLINE)\(maxncf,/\1N(maxncf, ec.maxncf,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->hnext\b/\1->ec.hnext/g
s/\b(SCALAR|ARRAY|INLINE)\(hnext,/\1N(hnext, ec.hnext,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->h0_actual\b/\1->ec.h0_actual/g
s/\b(SCALAR|ARRAY|INLINE)\(h0_actual,/\1N(h0_actual, ec.h0_actual,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->err_norm\b/\1->ec.err_norm/g
s/\b(SCALAR|ARRAY|INLINE)\(err_norm,/\1N(err_norm, ec.err_norm,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->err_prev\b/\1->ec.err_prev/g
s/\b(SCALAR|ARRAY|INLINE)\(err_prev,/\1N(err_prev, ec.err_prev,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->ele\b/\1->ec.ele/g
s/\b(SCALAR|ARRAY|INLINE)\(ele,/\1N(ele, ec.ele,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->ewt\b/\1->ec.ewt/g
s/\b(SCALAR|ARRAY|INLINE)\(ewt,/\1N(ewt, ec.ewt,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->a_scaled\b/\1->ec.a_scaled/g
s/\b(SCALAR|ARRAY|INLINE)\(a_scaled,/\1N(a_scaled, ec.a_scaled,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->a_step\b/\1->ec.a_step/g
s/\b(SCALAR|ARRAY|INLINE)\(a_step,/\1N(a_step, ec.a_step,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->netf\b/\1->ec.netf/g
s/\b(SCALAR|ARRAY|INLINE)\(netf,/\1N(netf, ec.netf,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lambda_errcon\b/\1->ec.lambda_errcon/g
s/\b(SCALAR|ARRAY|INLINE)\(lambda_errcon,/\1N(lambda_errcon, ec.lambda_errcon,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lambda_atol\b/\1->ec.lambda_atol/g
s/\b(SCALAR|ARRAY|INLINE)\(lambda_atol,/\1N(lambda_atol, ec.lambda_atol,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->lambda_err\b/\1->ec.lambda_err/g
s/\b(SCALAR|ARRAY|INLINE)\(lambda_err,/\1N(lambda_err, ec.lambda_err,/g
# ---- dense: struct LGNDenseRec (the last step, for dense output)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->tprev\b/\1->dense.tprev/g
s/\b(SCALAR|ARRAY|INLINE)\(tprev,/\1N(tprev, dense.tprev,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->dense_valid\b/\1->dense.valid/g
s/\b(SCALAR|ARRAY|INLINE)\(dense_valid,/\1N(dense_valid, dense.valid,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->incr\b/\1->dense.incr/g
s/\b(SCALAR|ARRAY|INLINE)\(incr,/\1N(incr, dense.incr,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->zero_nv\b/\1->dense.zero_nv/g
s/\b(SCALAR|ARRAY|INLINE)\(zero_nv,/\1N(zero_nv, dense.zero_nv,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->dense_work\b/\1->dense.work/g
s/\b(SCALAR|ARRAY|INLINE)\(dense_work,/\1N(dense_work, dense.work,/g
# ---- out: struct LGNOutputRec (what LGNSolve and LGNGetDky return)
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_consistent\b/\1->out.consistent/g
s/\b(SCALAR|ARRAY|INLINE)\(out_consistent,/\1N(out_consistent, out.consistent,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_project\b/\1->out.project/g
s/\b(SCALAR|ARRAY|INLINE)\(out_project,/\1N(out_project, out.project,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_valid\b/\1->out.valid/g
s/\b(SCALAR|ARRAY|INLINE)\(out_valid,/\1N(out_valid, out.valid,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_t\b/\1->out.t/g
s/\b(SCALAR|ARRAY|INLINE)\(out_t,/\1N(out_t, out.t,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_vdot\b/\1->out.vdot/g
s/\b(SCALAR|ARRAY|INLINE)\(out_vdot,/\1N(out_vdot, out.vdot,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_lambda\b/\1->out.lambda/g
s/\b(SCALAR|ARRAY|INLINE)\(out_lambda,/\1N(out_lambda, out.lambda,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_save\b/\1->out.save/g
s/\b(SCALAR|ARRAY|INLINE)\(out_save,/\1N(out_save, out.save,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_q\b/\1->out.q/g
s/\b(SCALAR|ARRAY|INLINE)\(out_q,/\1N(out_q, out.q,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_v\b/\1->out.v/g
s/\b(SCALAR|ARRAY|INLINE)\(out_v,/\1N(out_v, out.v,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_lq\b/\1->out.lq/g
s/\b(SCALAR|ARRAY|INLINE)\(out_lq,/\1N(out_lq, out.lq,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_lv\b/\1->out.lv/g
s/\b(SCALAR|ARRAY|INLINE)\(out_lv,/\1N(out_lv, out.lv,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_lt\b/\1->out.lt/g
s/\b(SCALAR|ARRAY|INLINE)\(out_lt,/\1N(out_lt, out.lt,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_lvalid\b/\1->out.lvalid/g
s/\b(SCALAR|ARRAY|INLINE)\(out_lvalid,/\1N(out_lvalid, out.lvalid,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_lwork\b/\1->out.lwork/g
s/\b(SCALAR|ARRAY|INLINE)\(out_lwork,/\1N(out_lwork, out.lwork,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_keep\b/\1->out.keep/g
s/\b(SCALAR|ARRAY|INLINE)\(out_keep,/\1N(out_keep, out.keep,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_keep_nv\b/\1->out.keep_nv/g
s/\b(SCALAR|ARRAY|INLINE)\(out_keep_nv,/\1N(out_keep_nv, out.keep_nv,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->out_keep_m\b/\1->out.keep_m/g
s/\b(SCALAR|ARRAY|INLINE)\(out_keep_m,/\1N(out_keep_m, out.keep_m,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nout\b/\1->out.n/g
s/\b(SCALAR|ARRAY|INLINE)\(nout,/\1N(nout, out.n,/g
# ---- rt: struct LGNRootRec (root finding (events))
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nrtfn\b/\1->rt.nrtfn/g
s/\b(SCALAR|ARRAY|INLINE)\(nrtfn,/\1N(nrtfn, rt.nrtfn,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->gfun\b/\1->rt.gfun/g
s/\b(SCALAR|ARRAY|INLINE)\(gfun,/\1N(gfun, rt.gfun,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->glo\b/\1->rt.glo/g
s/\b(SCALAR|ARRAY|INLINE)\(glo,/\1N(glo, rt.glo,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->ghi\b/\1->rt.ghi/g
s/\b(SCALAR|ARRAY|INLINE)\(ghi,/\1N(ghi, rt.ghi,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->grout\b/\1->rt.grout/g
s/\b(SCALAR|ARRAY|INLINE)\(grout,/\1N(grout, rt.grout,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->iroots\b/\1->rt.iroots/g
s/\b(SCALAR|ARRAY|INLINE)\(iroots,/\1N(iroots, rt.iroots,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->rootdir\b/\1->rt.rootdir/g
s/\b(SCALAR|ARRAY|INLINE)\(rootdir,/\1N(rootdir, rt.rootdir,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->gactive\b/\1->rt.gactive/g
s/\b(SCALAR|ARRAY|INLINE)\(gactive,/\1N(gactive, rt.gactive,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->rt_q\b/\1->rt.q/g
s/\b(SCALAR|ARRAY|INLINE)\(rt_q,/\1N(rt_q, rt.q,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->rt_v\b/\1->rt.v/g
s/\b(SCALAR|ARRAY|INLINE)\(rt_v,/\1N(rt_v, rt.v,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->rt_started\b/\1->rt.started/g
s/\b(SCALAR|ARRAY|INLINE)\(rt_started,/\1N(rt_started, rt.started,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->rt_pending\b/\1->rt.pending/g
s/\b(SCALAR|ARRAY|INLINE)\(rt_pending,/\1N(rt_pending, rt.pending,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->rt_first\b/\1->rt.first/g
s/\b(SCALAR|ARRAY|INLINE)\(rt_first,/\1N(rt_first, rt.first,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->rt_nowarn\b/\1->rt.nowarn/g
s/\b(SCALAR|ARRAY|INLINE)\(rt_nowarn,/\1N(rt_nowarn, rt.nowarn,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->tlo\b/\1->rt.tlo/g
s/\b(SCALAR|ARRAY|INLINE)\(tlo,/\1N(tlo, rt.tlo,/g
s/(\b(mem|mon|moff|mflip)|\(\*mem\)|\(\(LGNMem\)[A-Za-z0-9_.>-]+\))->nge\b/\1->rt.nge/g
s/\b(SCALAR|ARRAY|INLINE)\(nge,/\1N(nge, rt.nge,/g
