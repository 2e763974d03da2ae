/* known_counts_sparc.c -- the guest program of known_counts.c for SPARC V8 (qemu-sparc32plus), for
 * `make test-qemu-plugin-sparc`: ten_nops is 10 nops + retl + its delay-slot nop (12 instructions);
 * calls_ten_nops is save, call, delay nop, ret, restore (5) + ten_nops (12) = 17; tail_to_ten_nops
 * enters ten_nops by a branch (ba), which the fn counter must report as skipped. A call returns to
 * its address + 8, after its delay slot (SPARC Architecture Manual V8, B.24). */
#include <stdio.h>

void ten_nops(void);
void calls_ten_nops(void);
void tail_to_ten_nops(void);

__asm__(".text\n\t.align 4\n"
        "\t.global ten_nops\n\t.type ten_nops, #function\nten_nops:\n"
        "\tnop\n\tnop\n\tnop\n\tnop\n\tnop\n\tnop\n\tnop\n\tnop\n\tnop\n\tnop\n"
        "\tretl\n\tnop\n\t.size ten_nops, .-ten_nops\n"
        "\t.global calls_ten_nops\n\t.type calls_ten_nops, #function\ncalls_ten_nops:\n"
        "\tsave %sp, -96, %sp\n\tcall ten_nops\n\tnop\n\tret\n\trestore\n"
        "\t.size calls_ten_nops, .-calls_ten_nops\n"
        "\t.global tail_to_ten_nops\n\t.type tail_to_ten_nops, #function\ntail_to_ten_nops:\n"
        "\tba ten_nops\n\tnop\n\t.size tail_to_ten_nops, .-tail_to_ten_nops\n");

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
