/* Thin C layer for writing result files safely, for vemcontact_safe_file.
 *
 * gfortran's buffered I/O can report success when "no space left on device"
 * happens in a buffered write or at CLOSE, and its OPEN follows symbolic links.
 * Here every file is created under a unique temporary name in the folder of
 * its final name with O_CREAT|O_EXCL|O_NOFOLLOW (a planted link or file makes
 * the open fail instead of being followed), every write(2) is checked and
 * retried on short writes and EINTR, the data are fsync'ed and the close is
 * checked before rename(2) puts the file under its final name (atomic on POSIX
 * file systems: readers see the old file or the complete new one).
 *
 * Also here: the per-job lock (flock on JOB.lock) and the removal of a
 * previous run's files of a job.  Every function returns 0 or an errno value;
 * strerror text comes from vc_sf_strerror.  Only plain C types cross the
 * interface.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Suffix of every temporary: "." + final base name + "." + 12 random letters + ".tmp". */
#define VC_TMP_RANDOM 12

/* Copy of the folder part of `path` ("." when it has no '/'); 0 or ENAMETOOLONG. */
static int folder_of(const char *path, char *dir, size_t len) {
    const char *slash = strrchr(path, '/');
    size_t n;
    if (slash == NULL) {
        if (len < 2) return ENAMETOOLONG;
        strcpy(dir, ".");
        return 0;
    }
    n = (slash == path) ? 1 : (size_t)(slash - path);
    if (n + 1 > len) return ENAMETOOLONG;
    memcpy(dir, path, n);
    dir[n] = '\0';
    return 0;
}

/* fsync the folder of `path` so that a rename in it is durable.  File systems
 * that cannot sync a folder (EINVAL) are not an error. */
static int sync_folder(const char *path) {
    char dir[4096];
    int fd, rc = 0;
    if (folder_of(path, dir, sizeof dir) != 0) return 0;
    fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return 0;
    if (fsync(fd) != 0 && errno != EINVAL && errno != EROFS) rc = errno;
    close(fd);
    return rc;
}

/* Random letters for a temporary name (getrandom, with a clock fallback). */
static void random_letters(char *out, int n) {
    static const char abc[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    unsigned char raw[32];
    struct timespec ts;
    int i;
    if (getrandom(raw, (size_t)n, GRND_NONBLOCK) != (ssize_t)n) {
        clock_gettime(CLOCK_REALTIME, &ts);
        for (i = 0; i < n; i++) raw[i] = (unsigned char)((ts.tv_nsec >> (i % 24)) ^ (getpid() >> (i % 16)) ^ (i * 37));
    }
    for (i = 0; i < n; i++) out[i] = abc[raw[i] % (sizeof abc - 1)];
    out[n] = '\0';
}

/* Create a new, empty temporary file beside `final_path`, opened for writing,
 * never following a link.  Its name (NUL-terminated) goes to tmp[0..tmplen). */
int vc_sf_create(const char *final_path, int *fd, char *tmp, int tmplen) {
    const char *slash = strrchr(final_path, '/');
    const char *base = slash ? slash + 1 : final_path;
    size_t dirlen = slash ? (size_t)(slash - final_path + 1) : 0;
    char letters[VC_TMP_RANDOM + 1];
    int attempt;
    *fd = -1;
    if (*base == '\0') return EISDIR;
    for (attempt = 0; attempt < 100; attempt++) {
        random_letters(letters, VC_TMP_RANDOM);
        if ((size_t)snprintf(tmp, (size_t)tmplen, "%.*s.%s.%s.tmp", (int)dirlen, final_path, base, letters) >=
            (size_t)tmplen)
            return ENAMETOOLONG;
        *fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (*fd >= 0) return 0;
        if (errno != EEXIST) return errno;
    }
    return EEXIST;
}

/* Write all n bytes, retrying short writes and interrupted calls. */
int vc_sf_write(int fd, const char *buf, int64_t n) {
    while (n > 0) {
        size_t chunk = n > (int64_t)1 << 30 ? (size_t)1 << 30 : (size_t)n;
        ssize_t w = write(fd, buf, chunk);
        if (w < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        if (w == 0) return EIO;
        buf += w;
        n -= w;
    }
    return 0;
}

/* fsync and close `fd` (closed whatever happens). */
int vc_sf_close(int fd) {
    int rc = 0;
    if (fsync(fd) != 0 && errno != EINVAL) rc = errno;
    if (close(fd) != 0 && rc == 0 && errno != EINTR) rc = errno;
    return rc;
}

/* Put the closed file `tmp` under its final name and make the rename durable. */
int vc_sf_rename(const char *tmp, const char *final_path) {
    if (rename(tmp, final_path) != 0) return errno;
    return sync_folder(final_path);
}

/* fsync the file at `path` (not following links): for files another library
 * wrote and closed, before they are renamed. */
int vc_sf_sync_path(const char *path) {
    int fd = open(path, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return errno;
    return vc_sf_close(fd);
}

/* Remove `path` (a link itself, never its target); a missing file is fine. */
int vc_sf_unlink(const char *path) {
    if (unlink(path) != 0 && errno != ENOENT) return errno;
    return 0;
}

/* Create `path` afresh for appending lines: a file or link of that name is
 * removed first (never followed), then created with O_EXCL|O_NOFOLLOW. */
int vc_sf_create_fresh(const char *path, int *fd) {
    int rc = vc_sf_unlink(path);
    *fd = -1;
    if (rc != 0) return rc;
    *fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC | O_APPEND, 0666);
    return *fd < 0 ? errno : 0;
}

/* Take the exclusive lock of `path` without waiting: created if missing, never
 * through a link.  -1: another process holds it.  The descriptor stays
 * open (and the lock held) until the process ends or vc_sf_unlock. */
int vc_sf_lock(const char *path, int *fd) {
    *fd = open(path, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (*fd < 0) return errno;
    while (flock(*fd, LOCK_EX | LOCK_NB) != 0) {
        int e = errno;
        if (e == EINTR) continue;
        close(*fd);
        *fd = -1;
        return (e == EWOULDBLOCK || e == EAGAIN) ? -1 : e;
    }
    return 0;
}

void vc_sf_unlock(int fd) {
    if (fd >= 0) close(fd);
}

/* True when s[0..n) is one or more decimal digits. */
static int digits(const char *s, size_t n) {
    size_t i;
    if (n == 0) return 0;
    for (i = 0; i < n; i++)
        if (s[i] < '0' || s[i] > '9') return 0;
    return 1;
}

/* True when s[0..n) is digits or digits_digits (a step, or a step's increment). */
static int frame_digits(const char *s, size_t n) {
    const char *us = memchr(s, '_', n);
    if (us == NULL) return digits(s, n);
    return digits(s, (size_t)(us - s)) && digits(us + 1, n - (size_t)(us - s) - 1);
}

/* True when `name` is one of job's result files: JOB.pvd, JOB.h5, JOB.xdmf, JOB.mtx,
 * JOB_NNNN.vtu, JOB_contact_NNNN.vtu (and the increments' JOB_NNNN_MMMM.vtu,
 * JOB_contact_NNNN_MMMM.vtu), JOB_contact_pairK_NNNN.csv, JOB_print_NNNN.csv,
 * JOB_srm_NNNN.csv, JOB_phases.csv, JOB.sta. */
static int is_job_result(const char *name, size_t n, const char *job) {
    size_t j = strlen(job);
    const char *r;
    size_t m;
    if (n <= j || strncmp(name, job, j) != 0) return 0;
    r = name + j;
    m = n - j;
    if ((m == 4 && memcmp(r, ".pvd", 4) == 0) || (m == 3 && memcmp(r, ".h5", 3) == 0) ||
        (m == 4 && memcmp(r, ".mtx", 4) == 0) || (m == 5 && memcmp(r, ".xdmf", 5) == 0) ||
        (m == 4 && memcmp(r, ".sta", 4) == 0))
        return 1;
    if (r[0] != '_') return 0;
    r++;
    m--;
    if (m == 10 && memcmp(r, "phases.csv", 10) == 0) return 1;
    if (m > 4 && memcmp(r + m - 4, ".vtu", 4) == 0) {
        if (frame_digits(r, m - 4)) return 1;
        if (m > 12 && memcmp(r, "contact_", 8) == 0 && frame_digits(r + 8, m - 12)) return 1;
        return 0;
    }
    if (m > 10 && memcmp(r + m - 4, ".csv", 4) == 0 && memcmp(r, "print_", 6) == 0)
        return digits(r + 6, m - 10);
    if (m > 8 && memcmp(r + m - 4, ".csv", 4) == 0 && memcmp(r, "srm_", 4) == 0)
        return digits(r + 4, m - 8);
    if (m > 4 && memcmp(r + m - 4, ".csv", 4) == 0 && m > 12 && memcmp(r, "contact_pair", 12) == 0) {
        const char *p = r + 12, *end = r + m - 4;
        const char *us = memchr(p, '_', (size_t)(end - p));
        return us != NULL && digits(p, (size_t)(us - p)) && digits(us + 1, (size_t)(end - us - 1));
    }
    return 0;
}

/* True when `name` is a temporary of one of job's result files:
 * "." + result name + "." + VC_TMP_RANDOM letters + ".tmp". */
static int is_job_temporary(const char *name, size_t n, const char *job) {
    size_t tail = 1 + VC_TMP_RANDOM + 4;
    if (n < 1 + tail + 1 || name[0] != '.' || memcmp(name + n - 4, ".tmp", 4) != 0 || name[n - tail] != '.')
        return 0;
    return is_job_result(name + 1, n - 1 - tail, job);
}

/* Remove every result file and temporary of `job` in folder `dir` (files and
 * links themselves; never anything else, never following a link).  *nremoved
 * counts them; the first failure stops with its errno and the name in bad. */
int vc_sf_remove_job_files(const char *dir, const char *job, int *nremoved, char *bad, int badlen) {
    DIR *d;
    struct dirent *e;
    int dfd, rc = 0;
    *nremoved = 0;
    bad[0] = '\0';
    d = opendir(dir);
    if (d == NULL) return errno;
    dfd = dirfd(d);
    while ((e = readdir(d)) != NULL) {
        size_t n = strlen(e->d_name);
        if (!is_job_result(e->d_name, n, job) && !is_job_temporary(e->d_name, n, job)) continue;
        if (unlinkat(dfd, e->d_name, 0) != 0) {
            if (errno == ENOENT) continue;
            rc = errno;
            snprintf(bad, (size_t)badlen, "%s", e->d_name);
            break;
        }
        (*nremoved)++;
    }
    closedir(d);
    return rc;
}

/* strerror text of `err` into buf (NUL-terminated, at most len bytes). */
void vc_sf_strerror(int err, char *buf, int len) {
    snprintf(buf, (size_t)len, "%s", strerror(err));
}
