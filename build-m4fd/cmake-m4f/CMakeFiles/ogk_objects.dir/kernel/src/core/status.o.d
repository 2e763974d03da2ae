CMakeFiles/ogk_objects.dir/kernel/src/core/status.o: \
 /work/wt-utf/kernel/src/core/status.c \
 /work/wt-utf/kernel/include/ogk/status.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/float.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stddef.h
