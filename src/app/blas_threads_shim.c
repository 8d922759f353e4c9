/* BLAS thread count for vemcontact_app_blas_threads: the cores online, the
 * one-minute load average, and OpenBLAS's openblas_set_num_threads looked up at
 * run time (dlsym), so that the program links against any BLAS and the call is
 * skipped when the BLAS in the process is not OpenBLAS.  Debian can load two
 * copies of OpenBLAS (libopenblas.so.0 and the openblas-pthread libblas.so.3):
 * each copy found is set. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <unistd.h>

int vc_cores_online(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}

/* The one-minute load average, or -1 when the system does not tell. */
double vc_load_average(void)
{
    double l[1];
    return getloadavg(l, 1) == 1 ? l[0] : -1.0;
}

/* Set OpenBLAS's thread count to n in every copy loaded; returns how many copies were set. */
int vc_set_blas_threads(int n)
{
    static const char *libs[] = {"libopenblas.so.0", "libblas.so.3"};
    void (*set)(int), (*seen[3])(int);
    int nseen = 0, k, i, dup;
    void *h;
    for (k = -1; k < 2; k++) {
        h = k < 0 ? RTLD_DEFAULT : dlopen(libs[k], RTLD_NOW | RTLD_NOLOAD);
        if (h == NULL) continue;
        *(void **)(&set) = dlsym(h, "openblas_set_num_threads");
        if (set != NULL) {
            dup = 0;
            for (i = 0; i < nseen; i++) dup |= seen[i] == set;
            if (!dup) {
                set(n);
                seen[nseen++] = set;
            }
        }
        if (k >= 0) dlclose(h);
    }
    return nseen;
}
