
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-utf/kernel/src/blt/blt.c" "CMakeFiles/ogk_objects.dir/kernel/src/blt/blt.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/blt/blt.o.d"
  "/work/wt-utf/kernel/src/blt/blt_arc.c" "CMakeFiles/ogk_objects.dir/kernel/src/blt/blt_arc.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/blt/blt_arc.o.d"
  "/work/wt-utf/kernel/src/blt/blt_model.c" "CMakeFiles/ogk_objects.dir/kernel/src/blt/blt_model.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/blt/blt_model.o.d"
  "/work/wt-utf/kernel/src/contract/thrust_cmd.c" "CMakeFiles/ogk_objects.dir/kernel/src/contract/thrust_cmd.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/contract/thrust_cmd.o.d"
  "/work/wt-utf/kernel/src/core/chol.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/chol.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/chol.o.d"
  "/work/wt-utf/kernel/src/core/crc32.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/crc32.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/crc32.o.d"
  "/work/wt-utf/kernel/src/core/interp.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/interp.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/interp.o.d"
  "/work/wt-utf/kernel/src/core/linalg.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/linalg.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/linalg.o.d"
  "/work/wt-utf/kernel/src/core/mathutil.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/mathutil.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/mathutil.o.d"
  "/work/wt-utf/kernel/src/core/newton.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/newton.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/newton.o.d"
  "/work/wt-utf/kernel/src/core/rk4.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/rk4.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/rk4.o.d"
  "/work/wt-utf/kernel/src/core/status.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/status.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/status.o.d"
  "/work/wt-utf/kernel/src/core/table.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/table.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/table.o.d"
  "/work/wt-utf/kernel/src/core/version.c" "CMakeFiles/ogk_objects.dir/kernel/src/core/version.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/core/version.o.d"
  "/work/wt-utf/kernel/src/cpd/cpd.c" "CMakeFiles/ogk_objects.dir/kernel/src/cpd/cpd.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/cpd/cpd.o.d"
  "/work/wt-utf/kernel/src/mpsp/mpsp.c" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp.o.d"
  "/work/wt-utf/kernel/src/mpsp/mpsp_adjoint.c" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_adjoint.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_adjoint.o.d"
  "/work/wt-utf/kernel/src/mpsp/mpsp_bv.c" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_bv.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_bv.o.d"
  "/work/wt-utf/kernel/src/mpsp/mpsp_control.c" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_control.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_control.o.d"
  "/work/wt-utf/kernel/src/mpsp/mpsp_dynamics.c" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_dynamics.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_dynamics.o.d"
  "/work/wt-utf/kernel/src/mpsp/mpsp_propagate.c" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_propagate.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_propagate.o.d"
  "/work/wt-utf/kernel/src/mpsp/mpsp_sensitivity.c" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_sensitivity.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/mpsp/mpsp_sensitivity.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_condense.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_condense.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_condense.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_helio.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_helio.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_helio.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_hess.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_hess.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_hess.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_keepout.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_keepout.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_keepout.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_model.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_model.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_model.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_plan.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_plan.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_plan.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_problem.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_problem.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_problem.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_sens_cache.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_sens_cache.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_sens_cache.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_shoot.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_shoot.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_shoot.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_shoot_hess.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_shoot_hess.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_shoot_hess.o.d"
  "/work/wt-utf/kernel/src/nmpc/nmpc_sqp.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_sqp.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_sqp.o.d"
  "/work/wt-utf/kernel/src/nmpc/prox_model.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/prox_model.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/prox_model.o.d"
  "/work/wt-utf/kernel/src/nmpc/proximity.c" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/proximity.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nmpc/proximity.o.d"
  "/work/wt-utf/kernel/src/nog/cutoff.c" "CMakeFiles/ogk_objects.dir/kernel/src/nog/cutoff.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nog/cutoff.o.d"
  "/work/wt-utf/kernel/src/nog/nog.c" "CMakeFiles/ogk_objects.dir/kernel/src/nog/nog.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nog/nog.o.d"
  "/work/wt-utf/kernel/src/nog/nog_deprecated.c" "CMakeFiles/ogk_objects.dir/kernel/src/nog/nog_deprecated.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nog/nog_deprecated.o.d"
  "/work/wt-utf/kernel/src/nog/terminal.c" "CMakeFiles/ogk_objects.dir/kernel/src/nog/terminal.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/nog/terminal.o.d"
  "/work/wt-utf/kernel/src/qp/qp.c" "CMakeFiles/ogk_objects.dir/kernel/src/qp/qp.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/qp/qp.o.d"
  "/work/wt-utf/kernel/src/qp/qp_blas.c" "CMakeFiles/ogk_objects.dir/kernel/src/qp/qp_blas.o" "gcc" "CMakeFiles/ogk_objects.dir/kernel/src/qp/qp_blas.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
