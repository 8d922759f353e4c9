/* cholmod_ref: CHOLMOD's own default path on a Matrix Market matrix, the
 * reference for vemcontact's end-to-end solver time.
 *
 *   cholmod_ref A.mtx [b.mtx]
 *
 * A: "coordinate real symmetric" (either triangle stored) or a general file
 * holding one triangle.  b: dense Matrix Market vector; default b = A*ones.
 * Times cholmod_l_analyze (default ordering strategy, supernodal),
 * cholmod_l_factorize and cholmod_l_solve, one line per phase in seconds,
 * then nnz(L), the ordering chosen and the relative residual.
 *
 * Environment (for trying CHOLMOD's settings, issue 15):
 *   CHOLMOD_RELAX="n0,n1,n2,z0,z1,z2"  supernodal amalgamation (Common nrelax[3],
 *                                     zrelax[3]; CHOLMOD's defaults 4,16,48,0.8,0.1,0.05)
 *   CHOLMOD_ORDERING=amd|metis|nesdis  one ordering instead of CHOLMOD's default strategy
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cholmod.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *ordering_name(int o)
{
    static const char *names[] = {"natural", "given", "amd", "metis", "nesdis", "colamd",
                                  "postordered"};
    return (o >= 0 && o <= 6) ? names[o] : "unknown";
}

static int fail(const char *what, cholmod_common *c)
{
    fprintf(stderr, "cholmod_ref: %s failed (CHOLMOD status %d)\n", what, c->status);
    return 1;
}

int main(int argc, char **argv)
{
    cholmod_common common, *c = &common;
    cholmod_sparse *a;
    cholmod_dense *b, *x, *r;
    cholmod_factor *l;
    FILE *f;
    double t0, t_read, t_analyze, t_factorize, t_solve, one[2] = {1, 0}, mone[2] = {-1, 0};
    double rnorm, bnorm;
    int status = 0;

    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: cholmod_ref A.mtx [b.mtx]\n");
        return 2;
    }
    cholmod_l_start(c);
    c->supernodal = CHOLMOD_SUPERNODAL; /* as vemcontact does; the default picks it too for 2D FE matrices */
    {
        const char *relax = getenv("CHOLMOD_RELAX"), *ord = getenv("CHOLMOD_ORDERING");
        if (relax && sscanf(relax, "%zu,%zu,%zu,%lf,%lf,%lf", &c->nrelax[0], &c->nrelax[1], &c->nrelax[2],
                            &c->zrelax[0], &c->zrelax[1], &c->zrelax[2]) != 6) {
            fprintf(stderr, "cholmod_ref: CHOLMOD_RELAX takes n0,n1,n2,z0,z1,z2\n");
            return 2;
        }
        if (ord) {
            c->nmethods = 1;
            c->method[0].ordering = strcmp(ord, "amd") == 0     ? CHOLMOD_AMD
                                    : strcmp(ord, "metis") == 0 ? CHOLMOD_METIS
                                                                : CHOLMOD_NESDIS;
        }
        printf("relax      %zu,%zu,%zu,%g,%g,%g\n", c->nrelax[0], c->nrelax[1], c->nrelax[2], c->zrelax[0],
               c->zrelax[1], c->zrelax[2]);
    }

    t0 = now();
    f = fopen(argv[1], "r");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    a = cholmod_l_read_sparse(f, c);
    fclose(f);
    if (!a) return fail("reading the matrix", c);
    if (a->stype == 0) {
        /* a general file holding one triangle: say which */
        cholmod_sparse *t = cholmod_l_copy(a, 1, 1, c);
        cholmod_l_free_sparse(&a, c);
        a = t;
        if (!a) return fail("cholmod_l_copy", c);
    }
    if (argc == 3) {
        f = fopen(argv[2], "r");
        if (!f) {
            perror(argv[2]);
            return 1;
        }
        b = cholmod_l_read_dense(f, c);
        fclose(f);
        if (!b) return fail("reading the right-hand side", c);
    } else {
        cholmod_dense *ones = cholmod_l_ones(a->nrow, 1, CHOLMOD_REAL, c);
        b = cholmod_l_zeros(a->nrow, 1, CHOLMOD_REAL, c);
        if (!ones || !b) return fail("allocating b", c);
        cholmod_l_sdmult(a, 0, one, one, ones, b, c); /* b = A*ones (b starts at 0) */
        cholmod_l_free_dense(&ones, c);
    }
    t_read = now() - t0;

    t0 = now();
    l = cholmod_l_analyze(a, c);
    t_analyze = now() - t0;
    if (!l || c->status != CHOLMOD_OK) return fail("cholmod_l_analyze", c);

    t0 = now();
    cholmod_l_factorize(a, l, c);
    t_factorize = now() - t0;
    if (c->status != CHOLMOD_OK) return fail("cholmod_l_factorize", c);

    t0 = now();
    x = cholmod_l_solve(CHOLMOD_A, l, b, c);
    t_solve = now() - t0;
    if (!x || c->status != CHOLMOD_OK) return fail("cholmod_l_solve", c);

    r = cholmod_l_copy_dense(b, c);
    cholmod_l_sdmult(a, 0, mone, one, x, r, c); /* r = b - A x */
    rnorm = cholmod_l_norm_dense(r, 2, c);
    bnorm = cholmod_l_norm_dense(b, 2, c);

    printf("n          %ld\n", (long)a->nrow);
    printf("nnz(triu)  %ld\n", (long)cholmod_l_nnz(a, c));
    printf("read       %.3f s\n", t_read);
    printf("analyze    %.3f s\n", t_analyze);
    printf("factorize  %.3f s\n", t_factorize);
    printf("solve      %.3f s\n", t_solve);
    printf("total      %.3f s (analyze+factorize+solve)\n", t_analyze + t_factorize + t_solve);
    printf("nnz(L)     %.0f\n", c->lnz);
    printf("flops      %.4g\n", c->fl);
    printf("ordering   %s\n", ordering_name(l->ordering));
    printf("supernodal %s\n", l->is_super ? "yes" : "no");
    printf("residual   %.3e (||b-Ax||/||b||)\n", bnorm > 0 ? rnorm / bnorm : rnorm);

    cholmod_l_free_dense(&r, c);
    cholmod_l_free_dense(&x, c);
    cholmod_l_free_dense(&b, c);
    cholmod_l_free_factor(&l, c);
    cholmod_l_free_sparse(&a, c);
    cholmod_l_finish(c);
    return status;
}
