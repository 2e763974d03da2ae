CMakeFiles/ogk_objects.dir/kernel/src/nmpc/nmpc_helio.o: \
 /work/wt-utf/kernel/src/nmpc/nmpc_helio.c \
 /work/wt-utf/kernel/src/nmpc/nmpc_internal.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stdbool.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stddef.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stdint.h \
 /work/wt-utf/kernel/include/ogk/nmpc.h \
 /work/wt-utf/kernel/include/ogk/ocp.h \
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
 /usr/include/newlib/_ansi.h /work/wt-utf/kernel/include/ogk/qp.h \
 /work/wt-utf/kernel/include/ogk/types.h /usr/include/newlib/string.h \
 /usr/include/newlib/sys/string.h \
 /work/wt-utf/kernel/src/nmpc/../ogk_checks.h
