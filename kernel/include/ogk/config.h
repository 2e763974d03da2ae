/* ogk/config.h -- compile-time capacity limits of the kernel.
 *
 * Every buffer in the kernel is sized from these constants, so the memory
 * footprint of each context struct is known before the code runs. A build
 * may override any of them with -D on the compiler command line; the kernel
 * checks run-time dimensions against them and reports OGK_E_DIM. */
#ifndef OGK_CONFIG_H
#define OGK_CONFIG_H

#ifdef __cplusplus
extern "C" {
#endif

/* Largest square system (LU, Cholesky) and short side of a least-squares or
 * minimum-norm problem. */
#ifndef OGK_LA_MAX_N
#define OGK_LA_MAX_N 16u
#endif

/* Largest long side of a least-squares (rows) or minimum-norm (columns)
 * problem. MPSP stacks its Fourier weights along this side. */
#ifndef OGK_LA_MAX_LONG
#define OGK_LA_MAX_LONG 128u
#endif

/* Largest state vector the RK4 integrator propagates. */
#ifndef OGK_RK4_MAX_STATE
#define OGK_RK4_MAX_STATE 32u
#endif

/* Largest number of switching events one propagation may record. */
#ifndef OGK_RK4_MAX_SWITCHES
#define OGK_RK4_MAX_SWITCHES 32u
#endif

/* Largest number of RK4 steps of one propagation (fixed loop bound). */
#ifndef OGK_RK4_MAX_STEPS
#define OGK_RK4_MAX_STEPS 1000000u
#endif

/* Bisection iterations allowed to locate one switch (fixed loop bound;
 * 200 halvings shrink any double bracket to its last bit). */
#ifndef OGK_RK4_MAX_BISECTIONS
#define OGK_RK4_MAX_BISECTIONS 200u
#endif

/* Largest number of dimensions of one table-file entry. */
#ifndef OGK_TABLE_MAX_DIMS
#define OGK_TABLE_MAX_DIMS 4u
#endif

#ifdef __cplusplus
}
#endif

#endif /* OGK_CONFIG_H */
