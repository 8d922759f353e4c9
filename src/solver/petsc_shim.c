/* Thin C shim over PETSc's KSP for vemcontact_solver_petsc.
 *
 * One handle owns a PETSc matrix (the full symmetric matrix in AIJ format with
 * block size 2, built from the upper triangle in CSC that Fortran passes), the
 * KSP solver with its preconditioner, and for GAMG the rigid-body near null
 * space from the node coordinates.  Kinds: VC_PETSC_GAMG (CG + GAMG),
 * VC_PETSC_HYPRE (CG + hypre BoomerAMG), VC_PETSC_MUMPS (MUMPS Cholesky).
 * The defaults are set first and PETSc's options database (the PETSC_OPTIONS
 * environment variable and the string given to vc_petsc_initialize) may override
 * them, as KSPSetFromOptions does.
 *
 * PETSc (and MPI) are initialized on the first use, by vc_petsc_initialize, never
 * at program start: a run with CHOLMOD never touches MPI.  PETSc's error handler
 * is replaced by one that only returns the code; every PETSc call is checked and
 * its code and PETSc's message are handed back to Fortran (vc_petsc_message).
 *
 * Floating-point traps: the Fortran Debug build traps invalid, zero-divide and
 * overflow; PETSc, hypre and MUMPS raise such flags internally (as CHOLMOD does),
 * so every entry point runs with traps held off and restores the caller's
 * floating-point environment afterwards.
 *
 * Without PETSc (VC_HAVE_PETSC undefined: CMake did not find it) every entry
 * point returns VC_PETSC_NOT_BUILT.
 *
 * Under MPI (PETSC_COMM_WORLD of several processes) every process calls every
 * entry point with the same, replicated arguments (the driver runs on every
 * process); the matrix is distributed by rows, whole nodes (2 rows) per process,
 * each process inserting its own rows; the solution is gathered back to every
 * process, so that the callers stay identical.  With vc_petsc_distribute, each
 * process owns as many rows as it asks for (the driver's partition of the mesh)
 * and may pass its share of the matrix instead of the whole: the shares are
 * added (ADD_VALUES) into PETSc's matrix.
 */
#include <fenv.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Status codes; mirrored in src/solver/petsc.f90. */
enum {
    VC_PETSC_OK = 0,
    VC_PETSC_NOT_BUILT = 1,     /* vemcontact was built without PETSc */
    VC_PETSC_ERROR = 2,         /* a PETSc call failed; vc_petsc_message tells which */
    VC_PETSC_DIVERGED = 3,      /* the Krylov solver did not converge; *info = KSPConvergedReason */
    VC_PETSC_BAD_INPUT = 4,     /* sizes or pattern inconsistent; *info = 1-based column */
    VC_PETSC_ORDER = 5,         /* called out of order */
    VC_PETSC_NOMEM = 6
};

enum { VC_PETSC_GAMG = 1, VC_PETSC_HYPRE = 2, VC_PETSC_MUMPS = 3 };

#ifdef VC_HAVE_PETSC
#include <petscksp.h>

typedef struct {
    int kind;
    PetscInt n;
    PetscInt rstart, nloc; /* the rows of this process */
    Mat a;
    KSP ksp;
    Vec b, x;
    Vec xall;             /* x gathered on every process */
    VecScatter gather;
    PetscInt *row_ptr;    /* full CSR pattern, 0-based, in the caller's numbering */
    PetscInt *col_idx;
    PetscInt *perm;       /* PETSc's index k -> the caller's dof perm[k] */
    PetscInt *iperm;      /* the caller's dof -> PETSc's index */
    PetscInt *lptr;       /* this process's rows (PETSc's numbering): CSR offsets into pcol */
    PetscInt *pcol;       /* ... and their columns in PETSc's numbering */
    int64_t ncsc;         /* entries of the upper-triangle CSC */
    PetscInt *pos_upper;  /* CSC entry k -> its position in the CSR arrays (row i, column j) */
    PetscInt *pos_lower;  /* CSC entry k -> position of (j, i); -1 on the diagonal (positions
                           * are below row_ptr[n], a PetscInt, checked in vc_petsc_analyze) */
    PetscScalar *val;     /* CSR values */
    int set_up;           /* the KSP holds the operator of the last factorize */
    int64_t own_dofs;     /* rows of this process as vc_petsc_distribute asked; -1: an even split */
    int shares;           /* factorize gets this process's share of the matrix (vc_petsc_distribute) */
    int shared_values;    /* the matrix stores its values in val (one process, no perm) */
    PetscInt iterations;  /* of the last solve */
    PetscReal rnorm;      /* residual norm of the last solve */
    char message[512];
} vc_petsc_t;

/* The message of the last failure outside a handle (initialization). */
static char init_message[512];
static int initialized_here = 0;

static PetscErrorCode quiet_handler(MPI_Comm comm, int line, const char *func, const char *file,
                                    PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
    char *buf = (char *)ctx;
    (void)comm;
    (void)p;
    if (buf && buf[0] == '\0') {
        snprintf(buf, 512, "%s (PETSc error %d in %s, %s:%d)", mess ? mess : "", (int)n, func ? func : "?",
                 file ? file : "?", line);
    }
    return n;
}

/* Record the failure of a PETSc call in msg (unless one is already recorded). */
static int fail(PetscErrorCode ierr, const char *what, char *msg)
{
    const char *text = NULL;
    size_t used;
    if (msg[0] == '\0') {
        PetscErrorMessage(ierr, &text, NULL);
        snprintf(msg, 512, "%s: %s (PETSc error %d)", what, text ? text : "", (int)ierr);
    } else {
        used = strlen(msg);
        if (used < 400) snprintf(msg + used, 512 - used, " in %s", what);
    }
    return VC_PETSC_ERROR;
}

#define CHECK(call, what, msg)                                                                            \
    do {                                                                                                  \
        PetscErrorCode ierr_ = (call);                                                                    \
        if (ierr_) {                                                                                      \
            st = fail(ierr_, what, msg);                                                                  \
            goto done;                                                                                    \
        }                                                                                                 \
    } while (0)

/* Open MPI's start for a process that no MPI launcher started (a singleton, the
 * usual `vemcontact --solver gamg` or auto's gamg): by default its MPI_Init starts
 * a helper daemon (orted) and probes every transport (UCX, ...), 0.33-0.45 s of
 * a 5 s run on the peers' cantilever (docs/performance.md, "The peers'
 * cantilever").  A singleton only ever talks to itself, so it is told not to
 * start the daemon (ess_singleton_isolated; it then cannot spawn processes,
 * which vemcontact never does) and to use the point-to-point layer ob1 over the
 * self transport only: MPI_Init 0.05-0.09 s.  Only defaults: a variable the user
 * has set wins (setenv without overwrite), and nothing changes under mpirun (the
 * launcher's variables are set; the same ones as mpi_launched in petsc.f90) or
 * with another MPI. */
static void singleton_mpi_defaults(void)
{
#ifdef OPEN_MPI
    static const char *launched[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"};
    size_t k;
    for (k = 0; k < sizeof launched / sizeof launched[0]; k++)
        if (getenv(launched[k])) return;
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
    setenv("OMPI_MCA_pml", "ob1", 0);
    setenv("OMPI_MCA_btl", "self", 0);
#endif
}

int vc_petsc_initialize(const char *options)
{
    fenv_t env;
    int st = VC_PETSC_OK;
    PetscBool done_init = PETSC_FALSE;
    static char arg0[] = "vemcontact", arg1[] = "-no_signal_handler";
    static char *argv_store[3];
    static char **argv = argv_store;
    static int argc = 2;

    init_message[0] = '\0';
    feholdexcept(&env);
    PetscInitialized(&done_init);
    if (!done_init) {
        argv_store[0] = arg0;
        argv_store[1] = arg1;
        argv_store[2] = NULL;
        singleton_mpi_defaults();
        /* before PetscInitialize (the options database may be filled before it), so
         * that the options PetscInitialize itself reads take effect (-log_view set
         * after it would leave logging off and PetscFinalize failing on every process) */
        if (options && options[0] && PetscOptionsInsertString(NULL, options)) {
            snprintf(init_message, sizeof init_message, "PETSc options could not be read: '%.200s'", options);
            st = VC_PETSC_ERROR;
            goto done;
        }
        if (PetscInitialize(&argc, &argv, NULL, NULL)) {
            snprintf(init_message, sizeof init_message, "PETSc could not be initialized (is MPI usable?)");
            st = VC_PETSC_ERROR;
            goto done;
        }
        initialized_here = 1;
        PetscPushErrorHandler(quiet_handler, init_message);
    }
done:
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

void vc_petsc_finalize(void)
{
    fenv_t env;
    PetscBool done_init = PETSC_FALSE, done_fin = PETSC_FALSE;
    if (!initialized_here) return;
    feholdexcept(&env);
    PetscInitialized(&done_init);
    PetscFinalized(&done_fin);
    if (done_init && !done_fin) PetscFinalize();
    initialized_here = 0;
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
}

/* End every process of the run with status code: MPI_Abort, so that processes
 * waiting for this one in a collective operation do not wait forever.  Returns
 * only when MPI is not running. */
void vc_petsc_abort(int code)
{
    PetscBool done_init = PETSC_FALSE, done_fin = PETSC_FALSE;
    PetscInitialized(&done_init);
    PetscFinalized(&done_fin);
    if (done_init && !done_fin) MPI_Abort(PETSC_COMM_WORLD, code);
}

/* The number of MPI processes (1 before PETSc is initialized). */
int vc_petsc_comm_size(void)
{
    PetscMPIInt size = 1;
    PetscBool done_init = PETSC_FALSE;
    PetscInitialized(&done_init);
    if (done_init) MPI_Comm_size(PETSC_COMM_WORLD, &size);
    return (int)size;
}

/* This process's rank (0 before PETSc is initialized). */
int vc_petsc_comm_rank(void)
{
    PetscMPIInt rank = 0;
    PetscBool done_init = PETSC_FALSE;
    PetscInitialized(&done_init);
    if (done_init) MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    return (int)rank;
}

int vc_petsc_create(void **handle, int kind)
{
    vc_petsc_t *h;
    *handle = NULL;
    if (kind < VC_PETSC_GAMG || kind > VC_PETSC_MUMPS) return VC_PETSC_BAD_INPUT;
    h = calloc(1, sizeof(*h));
    if (!h) return VC_PETSC_NOMEM;
    h->kind = kind;
    h->own_dofs = -1;
    *handle = h;
    return VC_PETSC_OK;
}

static void free_objects(vc_petsc_t *h)
{
    if (h->ksp) KSPDestroy(&h->ksp);
    if (h->a) MatDestroy(&h->a);
    if (h->b) VecDestroy(&h->b);
    if (h->x) VecDestroy(&h->x);
    if (h->gather) VecScatterDestroy(&h->gather);
    if (h->xall) VecDestroy(&h->xall);
    free(h->row_ptr);
    free(h->col_idx);
    free(h->perm);
    free(h->iperm);
    free(h->lptr);
    free(h->pcol);
    h->perm = NULL;
    h->iperm = NULL;
    h->lptr = NULL;
    h->pcol = NULL;
    free(h->pos_upper);
    free(h->pos_lower);
    free(h->val);
    h->row_ptr = NULL;
    h->col_idx = NULL;
    h->pos_upper = NULL;
    h->pos_lower = NULL;
    h->val = NULL;
    h->set_up = 0;
    h->shared_values = 0;
    h->n = 0;
    h->ncsc = 0;
}

void vc_petsc_free(void **handle)
{
    fenv_t env;
    vc_petsc_t *h = *handle;
    if (!h) return;
    feholdexcept(&env);
    free_objects(h);
    free(h);
    *handle = NULL;
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
}

/* The message of the last failure of the handle (or of the initialization). */
void vc_petsc_message(void *handle, char *buf, int len)
{
    vc_petsc_t *h = handle;
    const char *m = h ? h->message : init_message;
    if (len <= 0) return;
    strncpy(buf, m, (size_t)len - 1);
    buf[len - 1] = '\0';
}

/* Build the full CSR pattern of the symmetric matrix whose upper triangle is the
 * 1-based CSC (col_ptr, row_idx) of order n, the matrix, the solver and, with
 * coords (2 per node, ndof = 2 nnode), the rigid-body near null space.  With
 * has_perm, PETSc numbers the dofs in the order perm (1-based, node by node: the
 * driver's partition lists each process's nodes together, so that its contiguous
 * share of the order is its part of the mesh); without it, in the caller's order. */
int vc_petsc_analyze(void *handle, int64_t n, const int64_t *col_ptr, const int32_t *row_idx, const double *coords,
                     int has_coords, const int32_t *perm, int has_perm, int64_t *info)
{
    fenv_t env;
    vc_petsc_t *h = handle;
    int st = VC_PETSC_OK;
    int64_t j, k, nnz, *fill = NULL;
    PetscInt *rowlen = NULL;
    Vec xy = NULL;
    MatNullSpace ns = NULL;
    PC pc;
    PetscInt *d_nnz = NULL, *o_nnz = NULL, r;
    PetscMPIInt size = 1, rank = 0;
    int64_t nn, base, rem, lnodes, snode;
    int own_storage = 0;

    *info = 0;
    if (!h) return VC_PETSC_ORDER;
    feholdexcept(&env);
    free_objects(h);
    h->message[0] = '\0';
    PetscPushErrorHandler(quiet_handler, h->message);
    if (n < 0 || n > 2147483647 || n % 2 != 0) {
        st = VC_PETSC_BAD_INPUT;
        goto done;
    }
    h->n = (PetscInt)n;
    nnz = col_ptr[n] - 1;
    h->ncsc = nnz;
    /* row lengths of the full matrix; the diagonal must be the last entry of a column */
    rowlen = calloc((size_t)n + 1, sizeof(PetscInt));
    h->row_ptr = malloc(((size_t)n + 1) * sizeof(PetscInt));
    fill = malloc(((size_t)n + 1) * sizeof(int64_t));
    h->pos_upper = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof(PetscInt));
    h->pos_lower = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof(PetscInt));
    if (!rowlen || !h->row_ptr || !fill || !h->pos_upper || !h->pos_lower) {
        st = VC_PETSC_NOMEM;
        goto done;
    }
    for (j = 0; j < n; j++) {
        for (k = col_ptr[j] - 1; k < col_ptr[j + 1] - 1; k++) {
            int64_t i = row_idx[k] - 1;
            if (i < 0 || i > j || (i == j && k != col_ptr[j + 1] - 2) ||
                (k > col_ptr[j] - 1 && row_idx[k - 1] - 1 >= i)) {
                *info = j + 1;
                st = VC_PETSC_BAD_INPUT;
                goto done;
            }
            rowlen[i]++;
            if (i != j) rowlen[j]++;
        }
    }
    h->row_ptr[0] = 0;
    for (j = 0; j < n; j++) {
        if ((int64_t)h->row_ptr[j] + rowlen[j] > 2147483647) {
            st = VC_PETSC_BAD_INPUT;
            goto done;
        }
        h->row_ptr[j + 1] = h->row_ptr[j] + rowlen[j];
    }
    h->col_idx = malloc((size_t)(h->row_ptr[n] > 0 ? h->row_ptr[n] : 1) * sizeof(PetscInt));
    h->val = calloc((size_t)(h->row_ptr[n] > 0 ? h->row_ptr[n] : 1), sizeof(PetscScalar));
    if (!h->col_idx || !h->val) {
        st = VC_PETSC_NOMEM;
        goto done;
    }
    /* Visiting the columns j in order, entry (i, j) of column j (i <= j, rows
     * increasing, diagonal last) puts column j into row i and column i into row
     * j: row j receives its entries left of the diagonal and the diagonal while
     * column j is visited, its entries right of it from the later columns, so
     * every row comes out sorted. */
    for (j = 0; j < n; j++) fill[j] = h->row_ptr[j];
    for (j = 0; j < n; j++) {
        for (k = col_ptr[j] - 1; k < col_ptr[j + 1] - 1; k++) {
            int64_t i = row_idx[k] - 1;
            /* entry (i, j), i <= j: row i, column j; and (j, i) in row j when i < j */
            h->pos_upper[k] = (PetscInt)fill[i];
            h->col_idx[fill[i]++] = (PetscInt)j;
            h->pos_lower[k] = -1;
            if (i != j) {
                h->pos_lower[k] = (PetscInt)fill[j];
                h->col_idx[fill[j]++] = (PetscInt)i;
            }
        }
    }

    /* the rows of this process: whole nodes, as evenly as they divide */
    MPI_Comm_size(PETSC_COMM_WORLD, &size);
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    nn = n / 2;
    base = nn / size;
    rem = nn % size;
    lnodes = base + (rank < rem ? 1 : 0);
    snode = rank * base + (rank < rem ? rank : rem);
    if (h->own_dofs >= 0) {
        /* the rows vc_petsc_distribute asked for, after those of the lower ranks */
        int64_t mine = h->own_dofs / 2, before = 0, total = 0;
        MPI_Exscan(&mine, &before, 1, MPI_INT64_T, MPI_SUM, PETSC_COMM_WORLD);
        MPI_Allreduce(&mine, &total, 1, MPI_INT64_T, MPI_SUM, PETSC_COMM_WORLD);
        if (rank == 0) before = 0;
        if (total != nn || h->own_dofs % 2 != 0) {
            st = VC_PETSC_BAD_INPUT;
            goto done;
        }
        lnodes = mine;
        snode = before;
    }
    h->rstart = (PetscInt)(2 * snode);
    h->nloc = (PetscInt)(2 * lnodes);
    h->perm = malloc((size_t)n * sizeof(PetscInt));
    h->iperm = malloc((size_t)n * sizeof(PetscInt));
    h->lptr = malloc(((size_t)h->nloc + 1) * sizeof(PetscInt));
    d_nnz = calloc((size_t)h->nloc + 1, sizeof(PetscInt));
    o_nnz = calloc((size_t)h->nloc + 1, sizeof(PetscInt));
    if (!h->perm || !h->iperm || !h->lptr || !d_nnz || !o_nnz) {
        st = VC_PETSC_NOMEM;
        goto done;
    }
    for (k = 0; k < n; k++) h->perm[k] = has_perm ? (PetscInt)(perm[k] - 1) : (PetscInt)k;
    for (k = 0; k < n; k++) h->iperm[k] = -1;
    for (k = 0; k < n; k++) {
        if (h->perm[k] < 0 || h->perm[k] >= n || h->iperm[h->perm[k]] >= 0) {
            *info = k + 1;
            st = VC_PETSC_BAD_INPUT;
            goto done;
        }
        h->iperm[h->perm[k]] = (PetscInt)k;
    }
    /* this process's rows: their columns in PETSc's numbering, in and off its block
     * (for MatSetValues and the preallocation; one process in the caller's numbering
     * hands its CSR arrays to PETSc instead, below, and needs neither) */
    own_storage = size == 1 && !has_perm;
    h->lptr[0] = 0;
    if (!own_storage) {
        for (r = 0; r < h->nloc; r++) {
            PetscInt i = h->perm[h->rstart + r];
            h->lptr[r + 1] = h->lptr[r] + (h->row_ptr[i + 1] - h->row_ptr[i]);
        }
        h->pcol = malloc((size_t)(h->lptr[h->nloc] > 0 ? h->lptr[h->nloc] : 1) * sizeof(PetscInt));
        if (!h->pcol) {
            st = VC_PETSC_NOMEM;
            goto done;
        }
        for (r = 0; r < h->nloc; r++) {
            PetscInt i = h->perm[h->rstart + r], q;
            for (q = h->row_ptr[i]; q < h->row_ptr[i + 1]; q++) {
                PetscInt c = h->iperm[h->col_idx[q]];
                h->pcol[h->lptr[r] + (q - h->row_ptr[i])] = c;
                if (c >= h->rstart && c < h->rstart + h->nloc)
                    d_nnz[r]++;
                else
                    o_nnz[r]++;
            }
        }
    }

    if (own_storage) {
        /* One process in the caller's numbering: the matrix is made on the handle's
         * own CSR arrays (row_ptr, col_idx, val are its storage; rows sorted), so
         * that vc_petsc_factorize only scatters the new values into val: no
         * MatSetValues (0.27-0.42 s for the 1e7 entries of the peers' cantilever,
         * docs/performance.md) and no second copy of the matrix. */
        CHECK(MatCreateSeqAIJWithArrays(PETSC_COMM_WORLD, h->n, h->n, h->row_ptr, h->col_idx, h->val, &h->a),
              "MatCreateSeqAIJWithArrays", h->message);
        CHECK(MatSetBlockSize(h->a, 2), "MatSetBlockSize", h->message);
        h->shared_values = 1;
    } else {
        CHECK(MatCreate(PETSC_COMM_WORLD, &h->a), "MatCreate", h->message);
        CHECK(MatSetSizes(h->a, h->nloc, h->nloc, h->n, h->n), "MatSetSizes", h->message);
        CHECK(MatSetType(h->a, MATAIJ), "MatSetType", h->message);
        CHECK(MatSetBlockSize(h->a, 2), "MatSetBlockSize", h->message);
        /* one of the two applies, by the matrix's type (one or several processes) */
        CHECK(MatSeqAIJSetPreallocation(h->a, 0, d_nnz), "MatSeqAIJSetPreallocation", h->message);
        CHECK(MatMPIAIJSetPreallocation(h->a, 0, d_nnz, 0, o_nnz), "MatMPIAIJSetPreallocation", h->message);
    }
    CHECK(MatSetOption(h->a, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption", h->message);
    CHECK(MatSetOption(h->a, MAT_SPD, PETSC_TRUE), "MatSetOption", h->message);
    CHECK(MatSetOption(h->a, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption", h->message);
    CHECK(MatCreateVecs(h->a, &h->x, &h->b), "MatCreateVecs", h->message);
    CHECK(VecScatterCreateToAll(h->x, &h->gather, &h->xall), "VecScatterCreateToAll", h->message);

    if (has_coords && h->kind == VC_PETSC_GAMG) {
        PetscScalar *p;
        CHECK(VecCreateMPI(PETSC_COMM_WORLD, h->nloc, h->n, &xy), "VecCreateMPI", h->message);
        CHECK(VecSetBlockSize(xy, 2), "VecSetBlockSize", h->message);
        CHECK(VecGetArray(xy, &p), "VecGetArray", h->message);
        for (j = 0; j < h->nloc; j++) p[j] = coords[h->perm[h->rstart + j]];
        CHECK(VecRestoreArray(xy, &p), "VecRestoreArray", h->message);
        CHECK(MatNullSpaceCreateRigidBody(xy, &ns), "MatNullSpaceCreateRigidBody", h->message);
        CHECK(MatSetNearNullSpace(h->a, ns), "MatSetNearNullSpace", h->message);
    }

    CHECK(KSPCreate(PETSC_COMM_WORLD, &h->ksp), "KSPCreate", h->message);
    CHECK(KSPGetPC(h->ksp, &pc), "KSPGetPC", h->message);
    switch (h->kind) {
    case VC_PETSC_GAMG:
    case VC_PETSC_HYPRE:
        CHECK(KSPSetType(h->ksp, KSPCG), "KSPSetType", h->message);
        /* the true residual |b - A x| <= rtol |b| (see petsc.f90 for rtol) */
        CHECK(KSPSetNormType(h->ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType", h->message);
        CHECK(KSPSetInitialGuessNonzero(h->ksp, PETSC_FALSE), "KSPSetInitialGuessNonzero", h->message);
        if (h->kind == VC_PETSC_GAMG) {
            CHECK(PCSetType(pc, PCGAMG), "PCSetType gamg", h->message);
        } else {
            CHECK(PCSetType(pc, PCHYPRE), "PCSetType hypre", h->message);
            CHECK(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType", h->message);
        }
        break;
    case VC_PETSC_MUMPS:
        CHECK(KSPSetType(h->ksp, KSPPREONLY), "KSPSetType", h->message);
        CHECK(PCSetType(pc, PCCHOLESKY), "PCSetType cholesky", h->message);
        CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType mumps", h->message);
        break;
    }
done:
    if (ns) MatNullSpaceDestroy(&ns);
    if (xy) VecDestroy(&xy);
    free(rowlen);
    free(fill);
    free(d_nnz);
    free(o_nnz);
    PetscPopErrorHandler();
    if (st != VC_PETSC_OK) free_objects(h);
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

/* New values (upper CSC, the analysed pattern: nnz entries) and the preconditioner or
 * factor set up; CG stops at |b - A x| <= rtol |b| or after maxit iterations.  A matrix
 * of another order or number of entries (a pattern rebuilt without a new analysis) is
 * refused: its values would land in the wrong places, or be read past their end. */
int vc_petsc_factorize(void *handle, int64_t n, int64_t nnz, const double *val, double rtol, int maxit)
{
    fenv_t env;
    vc_petsc_t *h = handle;
    int st = VC_PETSC_OK;
    int64_t k;
    PetscInt r;

    if (!h || !h->a) return VC_PETSC_ORDER;
    if (n != h->n || nnz != h->ncsc) return VC_PETSC_BAD_INPUT;
    feholdexcept(&env);
    h->message[0] = '\0';
    h->set_up = 0;
    PetscPushErrorHandler(quiet_handler, h->message);
    for (k = 0; k < h->ncsc; k++) {
        h->val[h->pos_upper[k]] = val[k];
        if (h->pos_lower[k] >= 0) h->val[h->pos_lower[k]] = val[k];
    }
    if (h->shared_values) {
        /* val is the matrix's storage (vc_petsc_analyze); giving its array back
         * marks the matrix as changed, so that the preconditioner is set up again */
        PetscScalar *storage = NULL;
        CHECK(MatSeqAIJGetArray(h->a, &storage), "MatSeqAIJGetArray", h->message);
        CHECK(MatSeqAIJRestoreArray(h->a, &storage), "MatSeqAIJRestoreArray", h->message);
    } else {
        if (h->shares) {
            /* the shares are added: start from zero after an earlier assembly */
            PetscBool assembled = PETSC_FALSE;
            CHECK(MatAssembled(h->a, &assembled), "MatAssembled", h->message);
            if (assembled) CHECK(MatZeroEntries(h->a), "MatZeroEntries", h->message);
        }
        for (r = 0; r < h->nloc; r++) {
            PetscInt grow = h->rstart + r, i = h->perm[grow];
            PetscInt len = h->row_ptr[i + 1] - h->row_ptr[i];
            CHECK(MatSetValues(h->a, 1, &grow, len, h->pcol + h->lptr[r], h->val + h->row_ptr[i],
                               h->shares ? ADD_VALUES : INSERT_VALUES),
                  "MatSetValues", h->message);
        }
        if (h->shares) {
            /* this share's entries in the rows of the other processes: only its non-zeros
             * (the rows its elements touch), sent by PETSc at assembly and added there */
            PetscInt g, q, m, *cols = NULL;
            PetscScalar *vals = NULL;
            PetscInt maxlen = 0;
            for (g = 0; g < h->n; g++)
                if (h->row_ptr[g + 1] - h->row_ptr[g] > maxlen) maxlen = h->row_ptr[g + 1] - h->row_ptr[g];
            cols = malloc((size_t)(maxlen > 0 ? maxlen : 1) * sizeof(PetscInt));
            vals = malloc((size_t)(maxlen > 0 ? maxlen : 1) * sizeof(PetscScalar));
            if (!cols || !vals) {
                free(cols);
                free(vals);
                st = VC_PETSC_NOMEM;
                goto done;
            }
            for (g = 0; g < h->n && st == VC_PETSC_OK; g++) {
                PetscInt i = h->perm[g];
                if (g >= h->rstart && g < h->rstart + h->nloc) continue;
                m = 0;
                for (q = h->row_ptr[i]; q < h->row_ptr[i + 1]; q++) {
                    if (h->val[q] == 0.0) continue;
                    cols[m] = h->iperm[h->col_idx[q]];
                    vals[m++] = h->val[q];
                }
                if (m > 0) {
                    PetscErrorCode ierr = MatSetValues(h->a, 1, &g, m, cols, vals, ADD_VALUES);
                    if (ierr) st = fail(ierr, "MatSetValues", h->message);
                }
            }
            free(cols);
            free(vals);
            if (st != VC_PETSC_OK) goto done;
        }
        CHECK(MatAssemblyBegin(h->a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin", h->message);
        CHECK(MatAssemblyEnd(h->a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd", h->message);
    }
    CHECK(KSPSetOperators(h->ksp, h->a, h->a), "KSPSetOperators", h->message);
    CHECK(KSPSetTolerances(h->ksp, rtol, PETSC_DEFAULT, PETSC_DEFAULT, maxit), "KSPSetTolerances", h->message);
    /* the user's PETSc options (-ksp_rtol, -pc_gamg_threshold, ...) override the defaults */
    CHECK(KSPSetFromOptions(h->ksp), "KSPSetFromOptions", h->message);
    CHECK(KSPSetUp(h->ksp), "KSPSetUp (preconditioner or factorization)", h->message);
    h->set_up = 1;
done:
    PetscPopErrorHandler();
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

/* x = A^-1 b for nrhs right-hand sides stored column after column. */
int vc_petsc_solve(void *handle, int64_t n, int64_t nrhs, const double *b, double *x, int64_t *info)
{
    fenv_t env;
    vc_petsc_t *h = handle;
    int st = VC_PETSC_OK;
    int64_t r;
    KSPConvergedReason reason;

    *info = 0;
    if (!h || !h->set_up) return VC_PETSC_ORDER;
    if (n != h->n) return VC_PETSC_BAD_INPUT;
    feholdexcept(&env);
    h->message[0] = '\0';
    h->iterations = 0;
    PetscPushErrorHandler(quiet_handler, h->message);
    for (r = 0; r < nrhs; r++) {
        PetscInt its = 0, i;
        PetscScalar *p;
        const PetscScalar *q;
        CHECK(VecGetArray(h->b, &p), "VecGetArray", h->message);
        for (i = 0; i < h->nloc; i++) p[i] = b[r * n + h->perm[h->rstart + i]];
        CHECK(VecRestoreArray(h->b, &p), "VecRestoreArray", h->message);
        CHECK(KSPSolve(h->ksp, h->b, h->x), "KSPSolve", h->message);
        CHECK(KSPGetConvergedReason(h->ksp, &reason), "KSPGetConvergedReason", h->message);
        CHECK(KSPGetIterationNumber(h->ksp, &its), "KSPGetIterationNumber", h->message);
        CHECK(KSPGetResidualNorm(h->ksp, &h->rnorm), "KSPGetResidualNorm", h->message);
        if (its > h->iterations) h->iterations = its;
        if (reason < 0) {
            *info = (int64_t)reason;
            snprintf(h->message, sizeof h->message, "%s after %d iterations (residual norm %.3e)",
                     KSPConvergedReasons[reason], (int)its, (double)h->rnorm);
            st = VC_PETSC_DIVERGED;
            goto done;
        }
        /* the solution on every process */
        CHECK(VecScatterBegin(h->gather, h->x, h->xall, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin",
              h->message);
        CHECK(VecScatterEnd(h->gather, h->x, h->xall, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd",
              h->message);
        CHECK(VecGetArrayRead(h->xall, &q), "VecGetArrayRead", h->message);
        for (i = 0; i < h->n; i++) x[r * n + h->perm[i]] = q[i];
        CHECK(VecRestoreArrayRead(h->xall, &q), "VecRestoreArrayRead", h->message);
    }
done:
    PetscPopErrorHandler();
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

/* Krylov iterations of the last solve (the largest over its right-hand sides). */
int vc_petsc_iterations(void *handle)
{
    vc_petsc_t *h = handle;
    return h ? (int)h->iterations : 0;
}

/* Before vc_petsc_analyze: this process owns own_dofs rows (whole nodes; the ranks
 * in order, the counts adding up to n), the first of the analysed permutation's
 * order after those of the lower ranks; with shares, vc_petsc_factorize gets this
 * process's share of the matrix, the matrix being the sum of the shares. */
int vc_petsc_distribute(void *handle, int64_t own_dofs, int shares)
{
    vc_petsc_t *h = handle;
    if (!h) return VC_PETSC_ORDER;
    h->own_dofs = own_dofs;
    h->shares = shares;
    return VC_PETSC_OK;
}

/* x = the sum of x over the processes, on every process. */
int vc_petsc_sum(double *x, int64_t n)
{
    fenv_t env;
    int st = VC_PETSC_OK;
    int64_t done = 0, chunk;
    PetscMPIInt size = 1;
    PetscBool done_init = PETSC_FALSE;
    PetscInitialized(&done_init);
    if (!done_init) return VC_PETSC_OK;
    MPI_Comm_size(PETSC_COMM_WORLD, &size);
    if (size == 1) return VC_PETSC_OK;
    feholdexcept(&env);
    while (done < n && st == VC_PETSC_OK) {
        chunk = n - done > 1073741824 ? 1073741824 : n - done;
        if (MPI_Allreduce(MPI_IN_PLACE, x + done, (int)chunk, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD) != MPI_SUCCESS)
            st = VC_PETSC_ERROR;
        done += chunk;
    }
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&env);
    return st;
}

#else /* without PETSc */

int vc_petsc_initialize(const char *options)
{
    (void)options;
    return VC_PETSC_NOT_BUILT;
}
void vc_petsc_finalize(void) {}
void vc_petsc_abort(int code) { (void)code; }
int vc_petsc_comm_size(void) { return 1; }
int vc_petsc_comm_rank(void) { return 0; }
int vc_petsc_create(void **handle, int kind)
{
    (void)kind;
    *handle = NULL;
    return VC_PETSC_NOT_BUILT;
}
void vc_petsc_free(void **handle) { *handle = NULL; }
void vc_petsc_message(void *handle, char *buf, int len)
{
    (void)handle;
    if (len > 0) {
        strncpy(buf, "vemcontact was built without PETSc", (size_t)len - 1);
        buf[len - 1] = '\0';
    }
}
int vc_petsc_analyze(void *handle, int64_t n, const int64_t *col_ptr, const int32_t *row_idx, const double *coords,
                     int has_coords, const int32_t *perm, int has_perm, int64_t *info)
{
    (void)handle, (void)n, (void)col_ptr, (void)row_idx, (void)coords, (void)has_coords, (void)perm, (void)has_perm;
    *info = 0;
    return VC_PETSC_NOT_BUILT;
}
int vc_petsc_factorize(void *handle, int64_t n, int64_t nnz, const double *val, double rtol, int maxit)
{
    (void)handle, (void)n, (void)nnz, (void)val, (void)rtol, (void)maxit;
    return VC_PETSC_NOT_BUILT;
}
int vc_petsc_solve(void *handle, int64_t n, int64_t nrhs, const double *b, double *x, int64_t *info)
{
    (void)handle, (void)n, (void)nrhs, (void)b, (void)x;
    *info = 0;
    return VC_PETSC_NOT_BUILT;
}
int vc_petsc_iterations(void *handle)
{
    (void)handle;
    return 0;
}
int vc_petsc_distribute(void *handle, int64_t own_dofs, int shares)
{
    (void)handle, (void)own_dofs, (void)shares;
    return VC_PETSC_NOT_BUILT;
}
int vc_petsc_sum(double *x, int64_t n)
{
    (void)x, (void)n;
    return VC_PETSC_OK;
}
#endif
