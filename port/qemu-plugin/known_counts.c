/* known_counts.c -- guest program with instruction counts known by
 * construction, for `make test-qemu-plugin`: ten_nops is 10 nops + bx lr
 * (11 instructions); calls_ten_nops is push, bl, pop (3) + ten_nops (11);
 * tail_to_ten_nops enters ten_nops by a branch (b), which the fn counter
 * must report as skipped, not count. */
#include <stdio.h>

__attribute__((naked, noinline)) void ten_nops(void)
{
    __asm__ volatile("nop\n\tnop\n\tnop\n\tnop\n\tnop\n\t"
                     "nop\n\tnop\n\tnop\n\tnop\n\tnop\n\t"
                     "bx lr\n\t");
}

__attribute__((naked, noinline)) void calls_ten_nops(void)
{
    __asm__ volatile("push {r4, lr}\n\t"
                     "bl ten_nops\n\t"
                     "pop {r4, pc}\n\t");
}

__attribute__((naked, noinline)) void tail_to_ten_nops(void)
{
    __asm__ volatile("nop\n\t"
                     "b ten_nops\n\t");
}

int main(void)
{
    for (volatile int i = 0; i < 5; ++i) {
        ten_nops();
    }
    calls_ten_nops();
    tail_to_ten_nops();
    printf("known_counts: ten_nops x6 by call (5 direct, 1 nested) + 1 by tail branch, "
           "calls_ten_nops x1\n");
    return 0;
}
