/* mpsp_control.c -- the MPSP control lambda_v = U = P(t) W: the Fourier
 * basis (eqs. 36-37, C.1) and its phase, U and |U| at one time or at two
 * times per pass (SSE2), the propagation's control cache and the U it keeps
 * for the sensitivity sweep. Costs: docs/design/mpsp.md, section 8. */
#include "mpsp_internal.h"

#include <math.h>
#include <string.h>

/* Largest phase step |omega (t - anchor_t)| taken by rotation in ogk_i_mpsp_phase:
 * the Taylor series below (to delta^8 and delta^9) then leave remainders
 * under delta^10/10! = 3e-20 and delta^11/11! = 1e-22, so the rotated cos and
 * sin are within a few ulp of cos() and sin(). With the Apophis grid
 * (omega h_max = pi/2000) one anchor serves 32 steps. */
#define MPSP_PHASE_REACH OGK_R(0.05)

void ogk_i_mpsp_phase(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *c1, ogk_real_t *s1)
{
    const ogk_real_t delta = dyn->omega * (t - dyn->anchor_t);

    if (dyn->anchor_ok && (OGK_FABS(delta) <= MPSP_PHASE_REACH)) {
        /* cos(a + d) = cos a cos d - sin a sin d, sin(a + d) = sin a cos d + cos a sin d */
        const ogk_real_t d2 = delta * delta;
        const ogk_real_t cd = OGK_R(1.0) - (d2 * (OGK_R(0.5) - (d2 * ((OGK_R(1.0) / OGK_R(24.0)) -
                          (d2 * ((OGK_R(1.0) / OGK_R(720.0)) - (d2 * (OGK_R(1.0) / OGK_R(40320.0)))))))));
        const ogk_real_t sd = delta * (OGK_R(1.0) - (d2 * ((OGK_R(1.0) / OGK_R(6.0)) - (d2 * ((OGK_R(1.0) / OGK_R(120.0)) -
                          (d2 * ((OGK_R(1.0) / OGK_R(5040.0)) - (d2 * (OGK_R(1.0) / OGK_R(362880.0))))))))));
        *c1 = (dyn->anchor_c * cd) - (dyn->anchor_s * sd);
        *s1 = (dyn->anchor_s * cd) + (dyn->anchor_c * sd);
    } else {
        const ogk_real_t theta = dyn->omega * (t - dyn->t_ref);
        dyn->anchor_t = t;
        dyn->anchor_c = OGK_COS(theta);
        dyn->anchor_s = OGK_SIN(theta);
        dyn->anchor_ok = true;
        *c1 = dyn->anchor_c;
        *s1 = dyn->anchor_s;
    }
}

/* h = [1/2, cos th, sin th, ..., cos n th, sin n th] (eq. C.1 with
 * th = omega (t - t_ref)), or [1/2, cos th, ..., cos 2n th] for the cosine
 * kind; the harmonics by the angle-addition recurrence (two trigonometric
 * calls per time, error growth ~k eps). */
void ogk_i_mpsp_basis(const ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *h, ogk_real_t *hdot) /* NOLINT(bugprone-easily-swappable-parameters): eq. (16) order x, u; FD-checked by the unit tests */
{
    const ogk_real_t theta = dyn->omega * (t - dyn->t_ref);
    const ogk_real_t c1 = OGK_COS(theta);
    const ogk_real_t s1 = OGK_SIN(theta);
    const size_t last = dyn->n_basis - 1u; /* 2n */
    const bool cosine = (dyn->kind == OGK_MPSP_BASIS_COSINE);
    ogk_real_t cn = c1;
    ogk_real_t sn = s1;
    size_t k;

    h[0] = OGK_R(0.5);
    if (hdot != NULL) {
        hdot[0] = OGK_R(0.0);
    }
    for (k = 1u; (cosine ? k : (2u * k)) <= last; ++k) { /* k <= n harmonics */
        const ogk_real_t kw = (ogk_real_t)k * dyn->omega;
        if (cosine) {
            h[k] = cn;
            if (hdot != NULL) {
                hdot[k] = -kw * sn;
            }
        } else {
            h[(2u * k) - 1u] = cn;
            h[2u * k] = sn;
            if (hdot != NULL) {
                hdot[(2u * k) - 1u] = -kw * sn;
                hdot[2u * k] = kw * cn;
            }
        }
        {
            const ogk_real_t c_next = (cn * c1) - (sn * s1);
            sn = (sn * c1) + (cn * s1);
            cn = c_next;
        }
    }
    /* Every one of the n_basis entries is written: an even n_basis (never made by
     * ogk_mpsp_init, which sets 2 n + 1) leaves a last entry the harmonics do not
     * reach; it is zeroed instead of left indeterminate (clang-analyzer
     * core.UndefinedBinaryOperatorResult in ogk_i_mpsp_control_from_basis). */
    if (!cosine && (last % 2u) != 0u) {
        h[last] = OGK_R(0.0);
        if (hdot != NULL) {
            hdot[last] = OGK_R(0.0);
        }
    }
}

/* One pass over the basis for the three components (each sum in the order
 * q = 0, 1, ..., as control_cs and ogk_i_mpsp_basis_control); h_q at h[q * stride]
 * (stride 1: a plain basis row; OGK_MPSP_H_LANES: a row of the sensitivity
 * sample block, each entry held twice). */
void ogk_i_mpsp_control_from_basis(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *h, size_t stride, ogk_real_t *u)
{
    const size_t nb = dyn->n_basis;
    const ogk_real_t *w = dyn->w;
    ogk_real_t u0 = OGK_R(0.0);
    ogk_real_t u1 = OGK_R(0.0);
    ogk_real_t u2 = OGK_R(0.0);
    size_t q;
    for (q = 0u; q < nb; ++q) {
        const ogk_real_t hq = h[q * stride];
        u0 += hq * w[q];
        u1 += hq * w[nb + q];
        u2 += hq * w[(2u * nb) + q];
    }
    u[0] = u0;
    u[1] = u1;
    u[2] = u2;
}

/* U = P(t) W from the phase (c1, s1): the harmonics of ogk_i_mpsp_basis (same
 * recurrence) summed as they are made, in the order of
 * ogk_i_mpsp_control_from_basis; the propagation needs U, not h (eqs. 36-37). */
static void control_cs(const ogk_i_mpsp_dyn_t *dyn, ogk_real_t c1, ogk_real_t s1, ogk_real_t *u)
{
    const size_t nb = dyn->n_basis;
    const size_t last = nb - 1u; /* 2n */
    const ogk_real_t *w = dyn->w;
    ogk_real_t cn = c1;
    ogk_real_t sn = s1;
    ogk_real_t u0 = OGK_R(0.0);
    ogk_real_t u1 = OGK_R(0.0);
    ogk_real_t u2 = OGK_R(0.0);
    size_t k;

    u0 += OGK_R(0.5) * w[0];
    u1 += OGK_R(0.5) * w[nb];
    u2 += OGK_R(0.5) * w[2u * nb];
    if (dyn->kind == OGK_MPSP_BASIS_COSINE) {
        for (k = 1u; k < last; k += 2u) { /* cos k theta, k = 1..2n, two per pass */
            ogk_real_t c2;
            ogk_real_t s2;
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            u0 += c2 * w[k + 1u];
            u1 += c2 * w[nb + k + 1u];
            u2 += c2 * w[(2u * nb) + k + 1u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if (k == last) { /* an odd 2n (never made by ogk_mpsp_init) */
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
        }
    } else {
        /* cos k theta, sin k theta, k = 1..n, two harmonics per pass (the
         * recurrence then needs no register copies) */
        for (k = 1u; ((2u * k) + 2u) <= last; k += 2u) {
            const size_t ic = (2u * k) - 1u;
            ogk_real_t c2;
            ogk_real_t s2;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            u0 += c2 * w[ic + 2u];
            u0 += s2 * w[ic + 3u];
            u1 += c2 * w[nb + ic + 2u];
            u1 += s2 * w[nb + ic + 3u];
            u2 += c2 * w[(2u * nb) + ic + 2u];
            u2 += s2 * w[(2u * nb) + ic + 3u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if ((2u * k) <= last) { /* n odd: the last harmonic */
            const size_t ic = (2u * k) - 1u;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
        }
    }
    u[0] = u0;
    u[1] = u1;
    u[2] = u2;
}

void ogk_i_mpsp_basis_control(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *h, ogk_i_mpsp_uval_t *uv)
{
    const size_t nb = dyn->n_basis;
    const size_t last = nb - 1u; /* 2n */
    const ogk_real_t *w = dyn->w;
    ogk_real_t c1;
    ogk_real_t s1;
    ogk_real_t cn;
    ogk_real_t sn;
    ogk_real_t u0;
    ogk_real_t u1;
    ogk_real_t u2;
    size_t k;

    ogk_i_mpsp_phase(dyn, t, &c1, &s1);
    cn = c1;
    sn = s1;
    h[0] = OGK_R(0.5);
    u0 = OGK_R(0.5) * w[0];
    u1 = OGK_R(0.5) * w[nb];
    u2 = OGK_R(0.5) * w[2u * nb];
    if (dyn->kind == OGK_MPSP_BASIS_COSINE) {
        for (k = 1u; k < last; k += 2u) { /* two per pass */
            ogk_real_t c2;
            ogk_real_t s2;
            h[k] = cn;
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            h[k + 1u] = c2;
            u0 += c2 * w[k + 1u];
            u1 += c2 * w[nb + k + 1u];
            u2 += c2 * w[(2u * nb) + k + 1u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if (k == last) { /* an odd 2n (never made by ogk_mpsp_init) */
            h[k] = cn;
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
        }
    } else {
        for (k = 1u; ((2u * k) + 2u) <= last; k += 2u) { /* two harmonics per pass */
            const size_t ic = (2u * k) - 1u;
            ogk_real_t c2;
            ogk_real_t s2;
            h[ic] = cn;
            h[ic + 1u] = sn;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            h[ic + 2u] = c2;
            h[ic + 3u] = s2;
            u0 += c2 * w[ic + 2u];
            u0 += s2 * w[ic + 3u];
            u1 += c2 * w[nb + ic + 2u];
            u1 += s2 * w[nb + ic + 3u];
            u2 += c2 * w[(2u * nb) + ic + 2u];
            u2 += s2 * w[(2u * nb) + ic + 3u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if ((2u * k) <= last) { /* n odd: the last harmonic */
            const size_t ic = (2u * k) - 1u;
            h[ic] = cn;
            h[ic + 1u] = sn;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
        }
        if ((last % 2u) != 0u) {
            h[last] = OGK_R(0.0); /* an even n_basis, as in ogk_i_mpsp_basis */
        }
    }
    uv->u[0] = u0;
    uv->u[1] = u1;
    uv->u[2] = u2;
    uv->lam = OGK_SQRT((u0 * u0) + (u1 * u1) + (u2 * u2));
}

#if defined(__SSE2__)
/* U = P(t) W and |U| at two times in one pass (lane l: time t[l]; a 2-lane
 * variable v holds time l at v[l]): per lane the arithmetic of control_cs and
 * ogk_i_mpsp_basis_control in the same order, so the same numbers; phases taken in
 * the order t[0], t[1], with the anchor t[1]'s phase starts from kept for
 * undo_next. Each statement is a loop over the lanes, which gcc -O2 on x86-64
 * carries in SSE2 registers (SLP), the weights read from their doubled copy. */
static void control2(ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *t, ogk_i_mpsp_uval_t *uv)
{
    const size_t nb = dyn->n_basis;
    const size_t last = nb - 1u; /* 2n */
    const ogk_real_t *w2 = dyn->w2;
    const ogk_real_t *w2b = &dyn->w2[2u * nb];
    const ogk_real_t *w2c = &dyn->w2[4u * nb];
    ogk_real_t c1[2];
    ogk_real_t s1[2];
    ogk_real_t cn[2];
    ogk_real_t sn[2];
    ogk_real_t c2[2];
    ogk_real_t s2[2];
    ogk_real_t u0[2];
    ogk_real_t u1[2];
    ogk_real_t u2[2];
    size_t k;
    size_t l;

    ogk_i_mpsp_phase(dyn, t[0], &c1[0], &s1[0]);
    /* the anchor t[1]'s phase starts from (ogk_i_mpsp_control_at may undo it) */
    dyn->undo_t = dyn->anchor_t;
    dyn->undo_c = dyn->anchor_c;
    dyn->undo_s = dyn->anchor_s;
    dyn->undo_ok = dyn->anchor_ok;
    ogk_i_mpsp_phase(dyn, t[1], &c1[1], &s1[1]);
    for (l = 0u; l < 2u; ++l) {
        cn[l] = c1[l];
        sn[l] = s1[l];
        u0[l] = OGK_R(0.5) * w2[l];
        u1[l] = OGK_R(0.5) * w2b[l];
        u2[l] = OGK_R(0.5) * w2c[l];
    }
    if (dyn->kind == OGK_MPSP_BASIS_COSINE) {
        for (k = 1u; k < last; k += 2u) { /* two per pass */
            const size_t i0 = 2u * k;
            for (l = 0u; l < 2u; ++l) {
                u0[l] += cn[l] * w2[i0 + l];
                u1[l] += cn[l] * w2b[i0 + l];
                u2[l] += cn[l] * w2c[i0 + l];
                c2[l] = (cn[l] * c1[l]) - (sn[l] * s1[l]);
                s2[l] = (sn[l] * c1[l]) + (cn[l] * s1[l]);
                u0[l] += c2[l] * w2[i0 + 2u + l];
                u1[l] += c2[l] * w2b[i0 + 2u + l];
                u2[l] += c2[l] * w2c[i0 + 2u + l];
                cn[l] = (c2[l] * c1[l]) - (s2[l] * s1[l]);
                sn[l] = (s2[l] * c1[l]) + (c2[l] * s1[l]);
            }
        }
        if (k == last) { /* an odd 2n (never made by ogk_mpsp_init) */
            for (l = 0u; l < 2u; ++l) {
                u0[l] += cn[l] * w2[(2u * k) + l];
                u1[l] += cn[l] * w2b[(2u * k) + l];
                u2[l] += cn[l] * w2c[(2u * k) + l];
            }
        }
    } else {
        for (k = 1u; ((2u * k) + 2u) <= last; k += 2u) { /* two harmonics per pass */
            const size_t ic = (2u * k) - 1u;
            const size_t i0 = 2u * ic;
            for (l = 0u; l < 2u; ++l) {
                u0[l] += cn[l] * w2[i0 + l];
                u0[l] += sn[l] * w2[i0 + 2u + l];
                u1[l] += cn[l] * w2b[i0 + l];
                u1[l] += sn[l] * w2b[i0 + 2u + l];
                u2[l] += cn[l] * w2c[i0 + l];
                u2[l] += sn[l] * w2c[i0 + 2u + l];
                c2[l] = (cn[l] * c1[l]) - (sn[l] * s1[l]);
                s2[l] = (sn[l] * c1[l]) + (cn[l] * s1[l]);
                u0[l] += c2[l] * w2[i0 + 4u + l];
                u0[l] += s2[l] * w2[i0 + 6u + l];
                u1[l] += c2[l] * w2b[i0 + 4u + l];
                u1[l] += s2[l] * w2b[i0 + 6u + l];
                u2[l] += c2[l] * w2c[i0 + 4u + l];
                u2[l] += s2[l] * w2c[i0 + 6u + l];
                cn[l] = (c2[l] * c1[l]) - (s2[l] * s1[l]);
                sn[l] = (s2[l] * c1[l]) + (c2[l] * s1[l]);
            }
        }
        if ((2u * k) <= last) { /* n odd: the last harmonic */
            const size_t ic = (2u * k) - 1u;
            const size_t i0 = 2u * ic;
            for (l = 0u; l < 2u; ++l) {
                u0[l] += cn[l] * w2[i0 + l];
                u0[l] += sn[l] * w2[i0 + 2u + l];
                u1[l] += cn[l] * w2b[i0 + l];
                u1[l] += sn[l] * w2b[i0 + 2u + l];
                u2[l] += cn[l] * w2c[i0 + l];
                u2[l] += sn[l] * w2c[i0 + 2u + l];
            }
        }
        if ((last % 2u) != 0u) {
        }
    }
    for (l = 0u; l < 2u; ++l) {
        uv[l].u[0] = u0[l];
        uv[l].u[1] = u1[l];
        uv[l].u[2] = u2[l];
        uv[l].lam = OGK_SQRT((u0[l] * u0[l]) + (u1[l] * u1[l]) + (u2[l] * u2[l]));
    }
}

#endif

#if defined(__SSE2__)
/* h2[2 q] = h2[2 q + 1] = h_q (each entry twice: OGK_MPSP_H_LANES). */
static void put2(ogk_real_t *h2, size_t q, ogk_real_t v)
{
    h2[2u * q] = v;
    h2[(2u * q) + 1u] = v;
}

/* The basis rows of the sensitivity sample block at two times, each entry
 * twice (OGK_MPSP_H_LANES): the harmonics of ogk_i_mpsp_basis_control (the same
 * recurrence, phases taken in the order t[0], t[1]), without U, which the
 * sweep takes from the propagation (ogk_i_mpsp_keep_find). */
void ogk_i_mpsp_basis2(ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *t, ogk_real_t *h_a, ogk_real_t *h_b)
{
    const size_t last = dyn->n_basis - 1u; /* 2n */
    const bool cosine = (dyn->kind == OGK_MPSP_BASIS_COSINE);
    ogk_real_t c1[2];
    ogk_real_t s1[2];
    ogk_real_t cn[2];
    ogk_real_t sn[2];
    size_t k;
    size_t l;

    ogk_i_mpsp_phase(dyn, t[0], &c1[0], &s1[0]);
    ogk_i_mpsp_phase(dyn, t[1], &c1[1], &s1[1]);
    put2(h_a, 0u, OGK_R(0.5));
    put2(h_b, 0u, OGK_R(0.5));
    for (l = 0u; l < 2u; ++l) {
        cn[l] = c1[l];
        sn[l] = s1[l];
    }
    /* harmonic k: cos k th at q = k (cosine kind) or 2 k - 1, sin k th at 2 k;
     * one per pass (no sums to interleave), the recurrence of ogk_i_mpsp_basis */
    for (k = 1u; (cosine ? k : (2u * k)) <= last; ++k) {
        if (cosine) {
            put2(h_a, k, cn[0]);
            put2(h_b, k, cn[1]);
        } else {
            put2(h_a, (2u * k) - 1u, cn[0]);
            put2(h_b, (2u * k) - 1u, cn[1]);
            put2(h_a, 2u * k, sn[0]);
            put2(h_b, 2u * k, sn[1]);
        }
        for (l = 0u; l < 2u; ++l) {
            const ogk_real_t c_next = (cn[l] * c1[l]) - (sn[l] * s1[l]);
            sn[l] = (sn[l] * c1[l]) + (cn[l] * s1[l]);
            cn[l] = c_next;
        }
    }
    /* n_basis = 2 n + 1 (ogk_mpsp_init): every entry is written */
}

/* The slot of t in the kept U: the nearest half grid step. t0 <= t <= tf
 * (the propagation's and the sweep's times) gives 0 .. 2 n_steps + 1, inside
 * the table; the remainder only bounds the index for any t. */
static size_t keep_slot(const ogk_i_mpsp_dyn_t *dyn, ogk_real_t t)
{
    const ogk_real_t x = ((t - dyn->grid_t0) * dyn->keep_scale) + OGK_R(0.5);
    return ((size_t)x) % OGK_MPSP_KEEP_U_SLOTS;
}

bool ogk_i_mpsp_keep_find(const ogk_mpsp_t *ctx, const ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_i_mpsp_uval_t *uv)
{
    const size_t j = keep_slot(dyn, t);
    const bool found = (ctx->keep_t[j] == t);

    if (found) { /* a slot never written is never read */
        uv->u[0] = ctx->keep_u[4u * j];
        uv->u[1] = ctx->keep_u[(4u * j) + 1u];
        uv->u[2] = ctx->keep_u[(4u * j) + 2u];
        uv->lam = ctx->keep_u[(4u * j) + 3u];
    }
    return found;
}

/* U and |U| at t into the slot of t. */
static void keep_store(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, const ogk_i_mpsp_uval_t *uv)
{
    const size_t j = keep_slot(dyn, t);

    dyn->keep_t[j] = t;
    dyn->keep_u[4u * j] = uv->u[0];
    dyn->keep_u[(4u * j) + 1u] = uv->u[1];
    dyn->keep_u[(4u * j) + 2u] = uv->u[2];
    dyn->keep_u[(4u * j) + 3u] = uv->lam;
}
#endif

#if defined(__SSE2__)
/* When t is the midpoint of an RK4 step that starts at cache_t (its stage 1
 * asked U there) and ends at the next node of ogk_rk4_propagate's grid (t0 +
 * k h, the last one tf), the time ogk_rk4_step will ask at its stage 4, in its
 * arithmetic (t + dt with dt = t_next - t); false otherwise (a trial step of
 * the switch bisection, a step off the grid, the sensitivity sweep), and U is
 * then taken at t alone. */
static bool step_end_of_midpoint(const ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *t_end)
{
    bool found = false;

    if (dyn->cache_ok && (t > dyn->cache_t) && (t < dyn->grid_tf)) {
        const ogk_real_t t_start = dyn->cache_t;
        /* the grid node above t (t is inside a step, never on a node) */
        const ogk_real_t k_next = OGK_FLOOR((t - dyn->grid_t0) / dyn->grid_h) + OGK_R(1.0);
        ogk_real_t t_next = dyn->grid_t0 + (k_next * dyn->grid_h);
        if (!(t_next < dyn->grid_tf)) {
            t_next = dyn->grid_tf;
        }
        {
            const ogk_real_t dt = t_next - t_start;
            found = ((t_start + (OGK_R(0.5) * dt)) == t);
            *t_end = t_start + dt;
        }
    }
    return found;
}

/* U at the end of the step was made with the midpoint's but the step ended
 * elsewhere (a switch): the phase anchor goes back to what it was before that
 * end's phase, as if it had never been taken. */
static void undo_next(ogk_i_mpsp_dyn_t *dyn)
{
    dyn->anchor_t = dyn->undo_t;
    dyn->anchor_c = dyn->undo_c;
    dyn->anchor_s = dyn->undo_s;
    dyn->anchor_ok = dyn->undo_ok;
    dyn->next_ok = false;
}
#endif

/* U at t: the time asked last is kept (RK4 stages 2 and 3, and the end of a
 * step and the start of the next, share times). On SSE2 targets U at the
 * midpoint of a grid step and at its end are made in one pass (control2: the
 * same numbers, the phases taken in the order of the one-time path, midpoint
 * then end), the end's held for stage 4 and both kept for the sweep. */
void ogk_i_mpsp_control_at(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *u)
{
#if defined(__SSE2__)
    ogk_real_t t_end = OGK_R(0.0);
#endif

    if (dyn->cache_ok && (dyn->cache_t == t)) {
        /* kept */
#if defined(__SSE2__)
    } else if (dyn->next_ok && (dyn->next_t == t)) {
        dyn->cache_u[0] = dyn->next_u[0];
        dyn->cache_u[1] = dyn->next_u[1];
        dyn->cache_u[2] = dyn->next_u[2];
        dyn->cache_t = t;
        dyn->next_ok = false;
    } else if (dyn->pairing && step_end_of_midpoint(dyn, t, &t_end)) {
        ogk_real_t tt[2];
        ogk_i_mpsp_uval_t uv[2];
        if (dyn->next_ok) {
            undo_next(dyn);
        }
        tt[0] = t;
        tt[1] = t_end;
        control2(dyn, tt, uv);
        dyn->cache_u[0] = uv[0].u[0];
        dyn->cache_u[1] = uv[0].u[1];
        dyn->cache_u[2] = uv[0].u[2];
        dyn->cache_t = t;
        dyn->next_u[0] = uv[1].u[0];
        dyn->next_u[1] = uv[1].u[1];
        dyn->next_u[2] = uv[1].u[2];
        dyn->next_t = t_end;
        dyn->next_ok = true;
        keep_store(dyn, t, &uv[0]);
        keep_store(dyn, t_end, &uv[1]);
#endif
    } else {
        ogk_real_t c1;
        ogk_real_t s1;
#if defined(__SSE2__)
        if (dyn->next_ok) {
            undo_next(dyn);
        }
#endif
        ogk_i_mpsp_phase(dyn, t, &c1, &s1);
        control_cs(dyn, c1, s1, dyn->cache_u);
        dyn->cache_t = t;
        dyn->cache_ok = true;
    }
    u[0] = dyn->cache_u[0];
    u[1] = dyn->cache_u[1];
    u[2] = dyn->cache_u[2];
}
