/* The system's reason behind an HDF5 failure, for vemcontact_output_hdf5.
 *
 * HDF5's POSIX file driver records a failed write(2) on its error stack as
 * "... errno = 28, error message = 'No space left on device', ...".  The
 * Fortran API returns only -1, so this walks the default error stack (HDF5's
 * printing of it is switched off) and copies the first such text, letting the
 * message say why a results file could not be written.
 */
#include <string.h>

#include "hdf5.h"

typedef struct {
    char *buf;
    size_t len;
    int found;
} vc_reason_t;

static herr_t visit(unsigned n, const H5E_error2_t *err, void *data) {
    static const char key[] = "error message = '";
    vc_reason_t *r = (vc_reason_t *)data;
    const char *p, *q;
    size_t m;
    (void)n;
    if (r->found || err->desc == NULL) return 0;
    p = strstr(err->desc, key);
    if (p == NULL) return 0;
    p += sizeof key - 1;
    q = strchr(p, '\'');
    m = q ? (size_t)(q - p) : strlen(p);
    if (m >= r->len) m = r->len - 1;
    memcpy(r->buf, p, m);
    r->buf[m] = '\0';
    r->found = 1;
    return 0;
}

/* The system's error text of the current HDF5 error stack ("" if none). */
void vc_h5_system_reason(char *buf, int len) {
    vc_reason_t r;
    if (len <= 0) return;
    buf[0] = '\0';
    r.buf = buf;
    r.len = (size_t)len;
    r.found = 0;
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, visit, &r);
}
