/* metis_options: METIS_NodeND option variants on the node graph of a
 * 2-dof-per-node stiffness matrix, each followed by CHOLMOD's analysis with the
 * given permutation (as vemcontact does), so that the ordering's time and the
 * factorization's flops and nnz(L) are measured in one run (issue 15).
 *
 *   metis_options A.mtx [factorize]
 *
 * A: vemcontact --write-matrix output (symmetric, dofs 2i-1, 2i of node i).  For
 * each variant prints: METIS_NodeND seconds, cholmod_l_analyze_p seconds, nnz(L),
 * flops, and with a second argument the cholmod_l_factorize seconds; all times are
 * processor time of this process (run with OPENBLAS_NUM_THREADS=1).  The seed
 * variants show how much nnz(L) and flops move with METIS's random choices alone.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cholmod.h"
#include "metis.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); /* processor time: the machine is shared */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

struct variant {
    const char *name;
    int compress, nseps, niter, ufactor, ccorder, seed;
};

int main(int argc, char **argv)
{
    cholmod_common common, *c = &common;
    cholmod_sparse *a, *s;
    FILE *f;
    /* -1: METIS's default for that option */
    const struct variant vars[] = {
        {"default", -1, -1, -1, -1, -1, -1},
        {"seed=1", -1, -1, -1, -1, -1, 1},
        {"seed=2", -1, -1, -1, -1, -1, 2},
        {"compress=0", 0, -1, -1, -1, -1, -1},
        {"niter=1", -1, -1, 1, -1, -1, -1},
        {"niter=3", -1, -1, 3, -1, -1, -1},
        {"nseps=2", -1, 2, -1, -1, -1, -1},
        {"ufactor=1", -1, -1, -1, 1, -1, -1},
        {"ufactor=100", -1, -1, -1, 100, -1, -1},
        {"ccorder=1", -1, -1, -1, -1, 1, -1},
        {"default", -1, -1, -1, -1, -1, -1},
    };
    const int nvar = (int)(sizeof vars / sizeof vars[0]);

    if (argc < 2) {
        fprintf(stderr, "usage: metis_options A.mtx [factorize]\n");
        return 2;
    }
    cholmod_l_start(c);
    c->supernodal = CHOLMOD_SUPERNODAL;
    f = fopen(argv[1], "r");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    a = cholmod_l_read_sparse(f, c);
    fclose(f);
    if (!a) return 1;
    if (a->stype == 0) {
        cholmod_sparse *t = cholmod_l_copy(a, 1, 1, c);
        cholmod_l_free_sparse(&a, c);
        a = t;
    }
    /* both triangles, to read each node's neighbours */
    s = cholmod_l_copy(a, 0, 0, c);
    if (!s || a->nrow % 2 != 0) return 1;
    {
        const long n = (long)a->nrow, nn = n / 2;
        const long *ap = s->p, *ai = s->i;
        idx_t *xadj = malloc((size_t)(nn + 1) * sizeof(idx_t));
        idx_t *adj = malloc((size_t)ap[n] * sizeof(idx_t));
        idx_t *perm = malloc((size_t)nn * sizeof(idx_t)), *iperm = malloc((size_t)nn * sizeof(idx_t));
        long *mark = malloc((size_t)nn * sizeof(long));
        long *dperm = malloc((size_t)n * sizeof(long));
        idx_t nv = (idx_t)nn, options[METIS_NOPTIONS];
        long ne = 0;
        for (long v = 0; v < nn; v++) mark[v] = -1;
        xadj[0] = 0;
        for (long v = 0; v < nn; v++) {
            mark[v] = v;
            for (long d = 2 * v; d <= 2 * v + 1; d++)
                for (long k = ap[d]; k < ap[d + 1]; k++) {
                    long w = ai[k] / 2;
                    if (mark[w] != v) {
                        mark[w] = v;
                        adj[ne++] = (idx_t)w;
                    }
                }
            xadj[v + 1] = (idx_t)ne;
        }
        printf("n %ld, nodes %ld, graph edges %ld\n", n, nn, ne / 2);
        printf("variant,metis_s,analyze_s,nnzL,flops,factorize_s\n");
        for (int k = 0; k < nvar; k++) {
            double t0, tm, ta, tf = 0;
            cholmod_factor *l;
            METIS_SetDefaultOptions(options);
            if (vars[k].compress >= 0) options[METIS_OPTION_COMPRESS] = vars[k].compress;
            if (vars[k].nseps >= 0) options[METIS_OPTION_NSEPS] = vars[k].nseps;
            if (vars[k].niter >= 0) options[METIS_OPTION_NITER] = vars[k].niter;
            if (vars[k].ufactor >= 0) options[METIS_OPTION_UFACTOR] = vars[k].ufactor;
            if (vars[k].ccorder >= 0) options[METIS_OPTION_CCORDER] = vars[k].ccorder;
            if (vars[k].seed >= 0) options[METIS_OPTION_SEED] = vars[k].seed;
            t0 = now();
            if (METIS_NodeND(&nv, xadj, adj, NULL, options, perm, iperm) != METIS_OK) return 1;
            tm = now() - t0;
            for (long v = 0; v < nn; v++) {
                dperm[2 * v] = 2 * (long)perm[v];
                dperm[2 * v + 1] = 2 * (long)perm[v] + 1;
            }
            c->nmethods = 1;
            c->method[0].ordering = CHOLMOD_GIVEN;
            c->postorder = 1;
            t0 = now();
            l = cholmod_l_analyze_p(a, dperm, NULL, 0, c);
            ta = now() - t0;
            if (!l) return 1;
            if (argc > 2) {
                t0 = now();
                cholmod_l_factorize(a, l, c);
                tf = now() - t0;
            }
            printf("%s,%.3f,%.3f,%.0f,%.4g,%.3f\n", vars[k].name, tm, ta, c->lnz, c->fl, tf);
            fflush(stdout);
            cholmod_l_free_factor(&l, c);
        }
        free(xadj);
        free(adj);
        free(perm);
        free(iperm);
        free(mark);
        free(dperm);
    }
    cholmod_l_free_sparse(&s, c);
    cholmod_l_free_sparse(&a, c);
    cholmod_l_finish(c);
    return 0;
}
