CMakeFiles/ogk_objects.dir/kernel/src/cpd/cpd.o: \
 /work/wt-utf/kernel/src/cpd/cpd.c /work/wt-utf/kernel/include/ogk/cpd.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stdint.h \
 /work/wt-utf/kernel/include/ogk/mathutil.h \
 /work/wt-utf/kernel/include/ogk/status.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/float.h \
 /work/wt-utf/kernel/include/ogk/real.h /usr/include/newlib/math.h \
 /usr/include/newlib/sys/reent.h /usr/include/newlib/_ansi.h \
 /usr/include/newlib/newlib.h /usr/include/newlib/_newlib_version.h \
 /usr/include/newlib/sys/config.h /usr/include/newlib/machine/ieeefp.h \
 /usr/include/newlib/sys/features.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stddef.h \
 /usr/include/newlib/sys/_types.h /usr/include/newlib/machine/_types.h \
 /usr/include/newlib/machine/_default_types.h \
 /usr/include/newlib/sys/lock.h /usr/include/newlib/sys/cdefs.h \
 /usr/include/newlib/_ansi.h /work/wt-utf/kernel/include/ogk/types.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stdbool.h \
 /usr/include/newlib/string.h /usr/include/newlib/sys/string.h \
 /work/wt-utf/kernel/src/cpd/../ogk_checks.h \
 /work/wt-utf/kernel/src/cpd/../thrust_cmd_internal.h
