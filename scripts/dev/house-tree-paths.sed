# The folders of issue 32 (branch house-tree): old path of a source of src/
# -> its new path. Port a text that names the old files with
#   sed -i -E -f scripts/dev/house-tree-paths.sed FILE...
# First the references with src/ (and groups/ references, unchanged), then
# the bare names of the five files that were renamed, not only moved.
s#src/lgn_err\.([ch])\b#src/util/lgn_err.\1#g
s#src/lgn_argcheck\.([ch])\b#src/util/lgn_argcheck.\1#g
s#src/lgn_matops\.([ch])\b#src/util/lgn_matops.\1#g
s#src/lgn_sparse\.([ch])\b#src/util/lgn_sparse.\1#g
s#src/lgn_parallel\.([ch])\b#src/parallel/lgn_parallel.\1#g
s#src/lgn_halo\.([ch])\b#src/parallel/lgn_halo.\1#g
s#src/lgn_ghosts\.c\b#src/parallel/lgn_ghosts.c#g
s#src/lgn_joints\.c\b#src/mbs/lgn_joints.c#g
s#src/lgn_bodies\.c\b#src/mbs/lgn_bodies.c#g
s#src/lgn_dense_lu\.([ch])\b#src/linsol/dense_lu/lgn_dense_lu.\1#g
s#src/lgn_petsc\.c\b#src/linsol/petsc/lgn_petsc.c#g
s#src/lgn_klu_solve\.([ch])\b#src/linsol/klu_copy/lgn_klu_solve.\1#g
s#src/lgn_blockprec\.([ch])\b#src/linsol/blockprec/lgn_blockprec.\1#g
s#src/lgn_restart\.c\b#src/io/lgn_restart.c#g
s#src/lgn_vtk\.c\b#src/io/lgn_vtk.c#g
s#src/lgn\.c\b#src/core/lgn.c#g
s#src/lgn_mem\.c\b#src/core/lgn_mem.c#g
s#src/lgn_impl\.h\b#src/core/lgn_impl.h#g
s#src/lgn_calcic\.c\b#src/core/lgn_calcic.c#g
s#src/lgn_newton\.c\b#src/core/lgn_newton.c#g
s#src/lgn_output\.c\b#src/core/lgn_output.c#g
s#src/lgn_io\.c\b#src/core/lgn_setget.c#g
s#src/lgn_ic\.c\b#src/core/lgn_consistent_ic.c#g
s#src/lgn_dense\.c\b#src/core/lgn_dense_output.c#g
s#src/lgn_model\.c\b#src/model/lgn_model.c#g
s#src/lgn_dq\.c\b#src/model/lgn_dq.c#g
s#src/lgn_tangent\.c\b#src/model/lgn_tangent.c#g
s#src/lgn_redundancy\.c\b#src/model/lgn_redundancy.c#g
s#src/lgn_diag\.c\b#src/model/lgn_diag.c#g
s#src/lgn_ls\.c\b#src/linsys/lgn_ls.c#g
s#src/lgn_krylov\.c\b#src/linsys/lgn_krylov.c#g
s#src/lgn_matrix\.c\b#src/linsys/lgn_matrix.c#g
s#src/lgn_matrix_sparse\.c\b#src/linsys/lgn_matrix_sparse.c#g
s#src/lgn_root\.c\b#src/events/lgn_root.c#g
s#src/lgn_impact\.c\b#src/events/lgn_impact.c#g
s#src/lgn_methods\.([ch])\b#src/methods/lgn_methods.\1#g
s#src/lgn_kinematics\.c\b#src/methods/lgn_kinematics.c#g
s#src/lgn_step\.c\b#src/methods/newmark/lgn_newmark_step.c#g
s#src/lgn_adapt\.c\b#src/methods/newmark/lgn_newmark_adapt.c#g
s#src/lgn_errtest\.c\b#src/methods/newmark/lgn_newmark_errtest.c#g
s#src/lgn_bdf\.c\b#src/methods/bdf/lgn_bdf.c#g
s#\blgn_io\.c\b#lgn_setget.c#g
s#\blgn_ic\.c\b#lgn_consistent_ic.c#g
s#\blgn_dense\.c\b#lgn_dense_output.c#g
s#\blgn_step\.c\b#lgn_newmark_step.c#g
s#\blgn_adapt\.c\b#lgn_newmark_adapt.c#g
s#\blgn_errtest\.c\b#lgn_newmark_errtest.c#g
