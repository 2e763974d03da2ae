CMakeFiles/ogk_objects.dir/kernel/src/core/crc32.o: \
 /work/wt-utf/kernel/src/core/crc32.c \
 /work/wt-utf/kernel/include/ogk/crc32.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stddef.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/stdint.h \
 /work/wt-utf/kernel/include/ogk/status.h \
 /usr/lib/gcc/arm-none-eabi/12.2.1/include/float.h
