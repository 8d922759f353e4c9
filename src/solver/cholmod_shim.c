/* Thin C shim over CHOLMOD (SuiteSparse_long API) for vemcontact_solver_cholmod.
 *
 * One handle owns a cholmod_common, the upper-triangle matrix (pattern copied
 * once at analysis, values copied at every factorization) and the factor.
 * Only plain C types cross the interface, so Fortran binds to it with bind(C).
 * Indices come in 1-based from Fortran and are copied to 0-based
 * SuiteSparse_long arrays; the caller's arrays are never modified.
 *
 * Every function returns a VC_CHOLMOD_* status.  CHOLMOD's own printing is
 * switched off: errors reach the user only through the Fortran error object.
 *
 * Floating-point traps: the Fortran Debug build enables traps on invalid,
 * zero-divide and overflow for the whole process.  CHOLMOD and the BLAS
 * legitimately raise these flags internally (e.g. while probing a pivot that
 * turns out non-positive), so every entry point runs CHOLMOD with traps held
 * off and restores the caller's floating-point environment afterwards.
 */
#include <fenv.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cholmod.h"

/* Status codes; mirrored in src/solver/cholmod.f90. */
enum {
    VC_CHOLMOD_OK = 0,
    VC_CHOLMOD_NOMEM = 1,       /* out of memory */
    VC_CHOLMOD_BAD_INPUT = 2,   /* pattern or permutation invalid; *info = 1-based column/position */
    VC_CHOLMOD_NOT_POSDEF = 3,  /* *info = 1-based original dof of the failed pivot */
    VC_CHOLMOD_ORDER = 4,       /* called out of order (no analysis / no valid factor) */
    VC_CHOLMOD_MISMATCH = 5,    /* pattern or size differs from the analysed one */
    VC_CHOLMOD_TOO_LARGE = 6,   /* integer overflow inside CHOLMOD */
    VC_CHOLMOD_FAILED = 7       /* any other CHOLMOD error; *info = common->status */
};

typedef struct {
    cholmod_common c;
    cholmod_sparse *a;   /* upper triangle, stype = +1, 0-based */
    cholmod_factor *l;
    int factorized;      /* l holds a valid numeric factor of the current values */
} vc_cholmod_t;

/* Map a CHOLMOD common->status to a shim status. */
static int map_status(int status)
{
    switch (status) {
    case CHOLMOD_OK: return VC_CHOLMOD_OK;
    case CHOLMOD_OUT_OF_MEMORY: return VC_CHOLMOD_NOMEM;
    case CHOLMOD_TOO_LARGE: return VC_CHOLMOD_TOO_LARGE;
    case CHOLMOD_NOT_POSDEF: return VC_CHOLMOD_NOT_POSDEF;
    default: return VC_CHOLMOD_FAILED;
    }
}

static void free_matrices(vc_cholmod_t *h)
{
    if (h->l) cholmod_l_free_factor(&h->l, &h->c);
    if (h->a) cholmod_l_free_sparse(&h->a, &h->c);
    h->factorized = 0;
}

int vc_cholmod_create(void **handle)
{
    fenv_t env;
    vc_cholmod_t *h;
    int ok;

    *handle = NULL;
    h = calloc(1, sizeof(*h));
    if (!h) return VC_CHOLMOD_NOMEM;
    feholdexcept(&env);
    ok = cholmod_l_start(&h->c);
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    if (!ok || h->c.status != CHOLMOD_OK) {
        free(h);
        return VC_CHOLMOD_FAILED;
    }
    h->c.print = 0;                        /* errors come back as status codes only */
    h->c.supernodal = CHOLMOD_SUPERNODAL;  /* BLAS-3 factorization regardless of the flop estimate */
    *handle = h;
    return VC_CHOLMOD_OK;
}

/* Symbolic analysis of the n-by-n upper-triangle pattern (1-based CSC).
 * perm (1-based, perm[k-1] = original index eliminated k-th) is used when
 * has_perm != 0; otherwise CHOLMOD's default ordering strategy decides.
 * On VC_CHOLMOD_BAD_INPUT, *info names the offending column or position. */
int vc_cholmod_analyze(void *handle, int64_t n, const int64_t *col_ptr,
                       const int32_t *row_idx, int has_perm, const int32_t *perm,
                       int64_t *info)
{
    vc_cholmod_t *h = handle;
    SuiteSparse_long *ap, *ai, *uperm = NULL;
    int64_t nnz, j, p;
    fenv_t env;
    int st;

    *info = 0;
    if (!h) return VC_CHOLMOD_ORDER;
    free_matrices(h);
    if (n < 0) return VC_CHOLMOD_BAD_INPUT;

    /* Validate before handing to CHOLMOD: it trusts a "sorted" flag. */
    if (col_ptr[0] != 1) { *info = 1; return VC_CHOLMOD_BAD_INPUT; }
    for (j = 0; j < n; j++) {
        if (col_ptr[j + 1] < col_ptr[j]) { *info = j + 1; return VC_CHOLMOD_BAD_INPUT; }
        for (p = col_ptr[j] - 1; p < col_ptr[j + 1] - 1; p++) {
            /* rows strictly increasing, within 1..j+1 (upper triangle) */
            if (row_idx[p] < 1 || row_idx[p] > j + 1 ||
                (p > col_ptr[j] - 1 && row_idx[p] <= row_idx[p - 1])) {
                *info = j + 1;
                return VC_CHOLMOD_BAD_INPUT;
            }
        }
    }
    nnz = col_ptr[n] - 1;

    if (has_perm) {
        char *seen = calloc((size_t)(n > 0 ? n : 1), 1);
        if (!seen) return VC_CHOLMOD_NOMEM;
        for (j = 0; j < n; j++) {
            if (perm[j] < 1 || perm[j] > n || seen[perm[j] - 1]) {
                free(seen);
                *info = j + 1;
                return VC_CHOLMOD_BAD_INPUT;
            }
            seen[perm[j] - 1] = 1;
        }
        free(seen);
    }

    feholdexcept(&env);
    h->a = cholmod_l_allocate_sparse((size_t)n, (size_t)n, (size_t)(nnz > 0 ? nnz : 1),
                                     1 /* sorted */, 1 /* packed */, 1 /* upper */,
                                     CHOLMOD_REAL, &h->c);
    if (!h->a) {
        st = h->c.status == CHOLMOD_OK ? VC_CHOLMOD_FAILED : map_status(h->c.status);
        goto done;
    }
    ap = h->a->p;
    ai = h->a->i;
    for (j = 0; j <= n; j++) ap[j] = col_ptr[j] - 1;
    for (p = 0; p < nnz; p++) ai[p] = row_idx[p] - 1;
    /* the analysis reads only the pattern; keep the values defined */
    memset(h->a->x, 0, (size_t)(nnz > 0 ? nnz : 1) * sizeof(double));

    if (has_perm) {
        uperm = cholmod_l_malloc((size_t)(n > 0 ? n : 1), sizeof(SuiteSparse_long), &h->c);
        if (!uperm) {
            st = h->c.status == CHOLMOD_OK ? VC_CHOLMOD_FAILED : map_status(h->c.status);
            cholmod_l_free_sparse(&h->a, &h->c);
            goto done;
        }
        for (j = 0; j < n; j++) uperm[j] = perm[j] - 1;
        /* only the given ordering (default would also try AMD and keep the best);
         * the etree postorder stays on: it does not change nnz(L) and helps supernodes */
        h->c.nmethods = 1;
        h->c.method[0].ordering = CHOLMOD_GIVEN;
        h->l = cholmod_l_analyze_p(h->a, uperm, NULL, 0, &h->c);
    } else {
        h->c.nmethods = 0;  /* CHOLMOD's default: AMD, then METIS if AMD's fill is high */
        h->l = cholmod_l_analyze(h->a, &h->c);
    }
    if (!h->l || h->c.status != CHOLMOD_OK) {
        st = h->c.status == CHOLMOD_OK ? VC_CHOLMOD_FAILED : map_status(h->c.status);
        if (st == VC_CHOLMOD_FAILED) *info = h->c.status;
        if (h->l) cholmod_l_free_factor(&h->l, &h->c);
        cholmod_l_free_sparse(&h->a, &h->c);
        goto done;
    }
    st = VC_CHOLMOD_OK;
done:
    if (uperm) cholmod_l_free((size_t)(n > 0 ? n : 1), sizeof(SuiteSparse_long), uperm, &h->c);
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

/* Numeric factorization with new values on the analysed pattern.  The pattern
 * is passed again and compared, so a caller that changed it gets an error
 * instead of a wrong factor (O(nnz), small next to the factorization).
 * On VC_CHOLMOD_NOT_POSDEF, *info is the 1-based ORIGINAL index of the first
 * failing pivot (L->minor is in the permuted order, mapped back through L->Perm). */
int vc_cholmod_factorize(void *handle, int64_t n, const int64_t *col_ptr,
                         const int32_t *row_idx, const double *val, int64_t *info)
{
    vc_cholmod_t *h = handle;
    const SuiteSparse_long *ap, *ai, *lperm;
    int64_t nnz, j, p;
    fenv_t env;
    int ok, st;

    *info = 0;
    if (!h || !h->a || !h->l) return VC_CHOLMOD_ORDER;
    h->factorized = 0;
    if (n != (int64_t)h->a->nrow) return VC_CHOLMOD_MISMATCH;
    ap = h->a->p;
    ai = h->a->i;
    for (j = 0; j <= n; j++) {
        if (col_ptr[j] - 1 != ap[j]) { *info = j < n ? j + 1 : n; return VC_CHOLMOD_MISMATCH; }
    }
    nnz = ap[n];
    for (j = 0; j < n; j++) {
        for (p = ap[j]; p < ap[j + 1]; p++) {
            if (row_idx[p] - 1 != ai[p]) { *info = j + 1; return VC_CHOLMOD_MISMATCH; }
        }
    }
    memcpy(h->a->x, val, (size_t)nnz * sizeof(double));

    feholdexcept(&env);
    ok = cholmod_l_factorize(h->a, h->l, &h->c);
    if (ok && h->c.status == CHOLMOD_OK) {
        h->factorized = 1;
        st = VC_CHOLMOD_OK;
    } else if (ok && h->c.status == CHOLMOD_NOT_POSDEF) {
        st = VC_CHOLMOD_NOT_POSDEF;
        lperm = h->l->Perm;
        p = (int64_t)h->l->minor;
        if (p >= 0 && p < n) *info = (lperm ? lperm[p] : p) + 1;
    } else {
        st = h->c.status == CHOLMOD_OK ? VC_CHOLMOD_FAILED : map_status(h->c.status);
        *info = h->c.status;
    }
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

/* Solve A x = b for nrhs right-hand sides stored column by column with leading
 * dimension n in b and x.  b is only read. */
int vc_cholmod_solve(void *handle, int64_t n, int64_t nrhs, const double *b, double *x)
{
    vc_cholmod_t *h = handle;
    cholmod_dense bd, *xd;
    fenv_t env;
    int st;

    if (!h || !h->l || !h->factorized) return VC_CHOLMOD_ORDER;
    if (n != (int64_t)h->l->n || nrhs < 0) return VC_CHOLMOD_MISMATCH;
    if (nrhs == 0 || n == 0) return VC_CHOLMOD_OK;

    /* a dense header around the caller's b: CHOLMOD does not write to B */
    memset(&bd, 0, sizeof(bd));
    bd.nrow = (size_t)n;
    bd.ncol = (size_t)nrhs;
    bd.nzmax = (size_t)(n * nrhs);
    bd.d = (size_t)n;
    bd.x = (void *)b;
    bd.xtype = CHOLMOD_REAL;
    bd.dtype = CHOLMOD_DOUBLE;

    feholdexcept(&env);
    xd = cholmod_l_solve(CHOLMOD_A, h->l, &bd, &h->c);
    if (!xd || h->c.status != CHOLMOD_OK) {
        st = h->c.status == CHOLMOD_OK ? VC_CHOLMOD_FAILED : map_status(h->c.status);
    } else {
        memcpy(x, xd->x, (size_t)(n * nrhs) * sizeof(double));
        st = VC_CHOLMOD_OK;
    }
    if (xd) cholmod_l_free_dense(&xd, &h->c);
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

/* CHOLMOD's reciprocal condition estimate (min(diag L)/max(diag L))^2.
 * Returns VC_CHOLMOD_ORDER without a valid factor. */
int vc_cholmod_rcond(void *handle, double *rcond)
{
    vc_cholmod_t *h = handle;
    fenv_t env;
    int st;

    *rcond = -1.0;
    if (!h || !h->l || !h->factorized) return VC_CHOLMOD_ORDER;
    feholdexcept(&env);
    *rcond = cholmod_l_rcond(h->l, &h->c);
    st = (*rcond < 0.0 || h->c.status != CHOLMOD_OK) ? VC_CHOLMOD_FAILED : VC_CHOLMOD_OK;
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

/* Statistics of the most recent analysis: nnz(L) (fundamental, without the
 * zeros of supernodal amalgamation), the LL' flop count, the ordering used
 * (CHOLMOD_NATURAL ... CHOLMOD_POSTORDERED) and whether L is supernodal. */
int vc_cholmod_stats(void *handle, int64_t *nnz_factor, double *flops, int *ordering,
                     int *is_super)
{
    vc_cholmod_t *h = handle;

    *nnz_factor = 0;
    *flops = 0.0;
    *ordering = -1;
    *is_super = 0;
    if (!h || !h->l) return VC_CHOLMOD_ORDER;
    *nnz_factor = (int64_t)h->c.lnz;
    *flops = h->c.fl;
    *ordering = h->l->ordering;
    *is_super = h->l->is_super;
    return VC_CHOLMOD_OK;
}

/* The trailing block of the factor that holds the dofs `dofs` (ndofs of them,
 * 1-based original indices): p0 is the first position of the elimination order
 * (after CHOLMOD's postorder, through L->Perm) that holds one of them, and the
 * block is rows and columns p0..n-1 of L.  With A = P' L L' P, for b supported
 * on those positions, (A^-1 b) there is (L_tt L_tt')^-1 b_t: a forward
 * substitution stays in the trailing rows and the back substitution there needs
 * no other rows.  *mt = n - p0 is the size of the block. */
int vc_cholmod_trailing_size(void *handle, int64_t ndofs, const int32_t *dofs, int64_t *mt)
{
    vc_cholmod_t *h = handle;
    const SuiteSparse_long *lperm;
    SuiteSparse_long *pos;
    int64_t n, k, p0;

    *mt = 0;
    if (!h || !h->l || !h->factorized) return VC_CHOLMOD_ORDER;
    n = (int64_t)h->l->n;
    lperm = h->l->Perm;
    if (!lperm || ndofs < 1) return VC_CHOLMOD_BAD_INPUT;
    pos = malloc((size_t)(n > 0 ? n : 1) * sizeof(*pos));
    if (!pos) return VC_CHOLMOD_NOMEM;
    for (k = 0; k < n; k++) pos[lperm[k]] = k;
    p0 = n;
    for (k = 0; k < ndofs; k++) {
        if (dofs[k] < 1 || dofs[k] > n) { free(pos); return VC_CHOLMOD_BAD_INPUT; }
        if (pos[dofs[k] - 1] < p0) p0 = pos[dofs[k] - 1];
    }
    free(pos);
    *mt = n - p0;
    return VC_CHOLMOD_OK;
}

/* Copy the trailing mt x mt block of the supernodal factor L (lower triangle,
 * column-major, leading dimension mt; the strict upper triangle zero) into lt
 * and the original dofs (1-based) of its positions into dof.  Only an LL'
 * supernodal real factor is read: any other is VC_CHOLMOD_FAILED (the caller
 * falls back to full solves).  In a supernode of columns k1..k2-1 the values
 * of column j are px[s] + (j-k1)*nsrow + r for its row list pi[s]..pi[s+1]-1,
 * whose first k2-k1 rows are k1..k2-1 themselves (the rows above the diagonal
 * are not part of L). */
int vc_cholmod_trailing_block(void *handle, int64_t mt, double *lt, int64_t *dof)
{
    vc_cholmod_t *h = handle;
    cholmod_factor *l;
    const SuiteSparse_long *super, *pi, *px, *ls, *lperm;
    const double *lx;
    int64_t n, p0, s, j, r, k1, k2, nsrow, i;

    if (!h || !h->l || !h->factorized) return VC_CHOLMOD_ORDER;
    l = h->l;
    n = (int64_t)l->n;
    if (mt < 0 || mt > n) return VC_CHOLMOD_MISMATCH;
    if (!l->is_super || !l->is_ll || l->xtype != CHOLMOD_REAL || !l->Perm) return VC_CHOLMOD_FAILED;
    super = l->super;
    pi = l->pi;
    px = l->px;
    ls = l->s;
    lx = l->x;
    lperm = l->Perm;
    p0 = n - mt;
    memset(lt, 0, (size_t)(mt * mt > 0 ? mt * mt : 1) * sizeof(double));
    for (k1 = p0; k1 < n; k1++) dof[k1 - p0] = lperm[k1] + 1;
    for (s = (int64_t)l->nsuper - 1; s >= 0; s--) {
        k1 = super[s];
        k2 = super[s + 1];
        if (k2 <= p0) break;
        nsrow = pi[s + 1] - pi[s];
        for (j = (k1 > p0 ? k1 : p0); j < k2; j++) {
            for (r = j - k1; r < nsrow; r++) {
                i = ls[pi[s] + r];
                if (i < j || i >= n) return VC_CHOLMOD_FAILED;
                lt[(i - p0) + (j - p0) * mt] = lx[px[s] + (j - k1) * nsrow + r];
            }
        }
    }
    return VC_CHOLMOD_OK;
}

/* Free everything and null the handle; a null handle is fine. */
void vc_cholmod_free(void **handle)
{
    vc_cholmod_t *h = *handle;
    fenv_t env;

    if (!h) return;
    feholdexcept(&env);
    free_matrices(h);
    cholmod_l_finish(&h->c);
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    free(h);
    *handle = NULL;
}
