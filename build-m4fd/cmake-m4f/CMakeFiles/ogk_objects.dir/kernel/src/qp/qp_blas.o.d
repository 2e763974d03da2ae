CMakeFiles/ogk_objects.dir/kernel/src/qp/qp_blas.o: \
 /work/wt-utf/kernel/src/qp/qp_blas.c \
 /work/wt-utf/kernel/src/qp/qp_internal.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stdbool.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stddef.h \
 /work/wt-utf/kernel/include/ogk/status.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/float.h \
 /work/wt-utf/kernel/include/ogk/real.h /usr/include/newlib/math.h \
 /usr/include/newlib/sys/reent.h /usr/include/newlib/_ansi.h \
 /usr/include/newlib/newlib.h /usr/include/newlib/_newlib_version.h \
 /usr/include/newlib/sys/config.h /usr/include/newlib/machine/ieeefp.h \
 /usr/include/newlib/sys/features.h /usr/include/newlib/sys/_types.h \
 /usr/include/newlib/machine/_types.h \
 /usr/include/newlib/machine/_default_types.h \
 /usr/include/newlib/sys/lock.h /usr/include/newlib/sys/cdefs.h \
 /usr/include/newlib/_ansi.h \
 /work/wt-utf/kernel/src/qp/../chol_internal.h \
 /work/wt-utf/kernel/include/ogk/qp.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stdint.h
