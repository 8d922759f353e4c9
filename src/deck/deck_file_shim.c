/* Thin C layer for reading deck files, for vemcontact_deck_source.
 *
 * A deck or an *INCLUDE must be a regular file: the kind of the file is taken
 * from stat(2) before it is opened, because opening a FIFO without a writer
 * blocks for ever, and a pipe, a terminal or a device (/dev/stdin, /dev/urandom)
 * has no size to read it by.  Files of /proc and /sys say they are regular and
 * empty although reading gives data or an error (/proc/self/mem): an empty
 * regular file is therefore probed with a one-byte read, and refused when that
 * read gives anything but end of file.  Reads are made with read(2) in pieces
 * the caller chooses, so that a file can be checked as it arrives and given up
 * early (a huge line, a binary file) without reading the rest.
 * Only plain C types cross the interface.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Kinds returned by vc_deck_open (mirrored in src/deck/source.f90). */
enum {
    VC_KIND_REGULAR = 0,
    VC_KIND_DIRECTORY = 1,
    VC_KIND_FIFO = 2,
    VC_KIND_CHAR_DEVICE = 3,
    VC_KIND_BLOCK_DEVICE = 4,
    VC_KIND_SOCKET = 5,
    VC_KIND_PSEUDO = 6, /* says regular and empty, but reading gives data or an error */
    VC_KIND_OTHER = 7
};

/* Open `path` for reading when it is a regular file.  Returns 0 and sets *fd and
 * *size, or an errno value (*kind = -1), or -1 when the file exists but is not a
 * regular file (*kind says what it is; nothing is left open). */
int vc_deck_open(const char *path, int *fd, int64_t *size, int *kind) {
    struct stat st;
    int f;
    char probe;
    ssize_t got;
    *fd = -1;
    *size = 0;
    *kind = -1;
    if (stat(path, &st) != 0) return errno;
    if (S_ISDIR(st.st_mode)) *kind = VC_KIND_DIRECTORY;
    else if (S_ISFIFO(st.st_mode)) *kind = VC_KIND_FIFO;
    else if (S_ISCHR(st.st_mode)) *kind = VC_KIND_CHAR_DEVICE;
    else if (S_ISBLK(st.st_mode)) *kind = VC_KIND_BLOCK_DEVICE;
    else if (S_ISSOCK(st.st_mode)) *kind = VC_KIND_SOCKET;
    else if (!S_ISREG(st.st_mode)) *kind = VC_KIND_OTHER;
    if (*kind >= 0) return -1;
    /* O_NONBLOCK: should the file have been replaced by a FIFO since stat, the
     * open does not wait for a writer (the fstat below then refuses it) */
    f = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (f < 0) return errno;
    if (fstat(f, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(f);
        *kind = VC_KIND_OTHER;
        return -1;
    }
    if (st.st_size == 0) {
        do {
            got = read(f, &probe, 1);
        } while (got < 0 && errno == EINTR);
        if (got != 0) {
            close(f);
            *kind = VC_KIND_PSEUDO;
            return -1;
        }
        if (lseek(f, 0, SEEK_SET) != 0) {
            close(f);
            *kind = VC_KIND_PSEUDO;
            return -1;
        }
    }
    *kind = VC_KIND_REGULAR;
    *fd = f;
    *size = (int64_t)st.st_size;
    return 0;
}

/* Read up to `n` bytes into `buf` (retrying short reads and EINTR).  Returns the
 * number read (less than `n` only at end of file) or -errno. */
int64_t vc_deck_read(int fd, char *buf, int64_t n) {
    int64_t done = 0;
    ssize_t got;
    while (done < n) {
        got = read(fd, buf + done, (size_t)(n - done));
        if (got < 0) {
            if (errno == EINTR) continue;
            return -(int64_t)errno;
        }
        if (got == 0) break;
        done += got;
    }
    return done;
}

void vc_deck_close(int fd) {
    if (fd >= 0) close(fd);
}

/* strerror text of `code` into buf (NUL-terminated, at most len bytes). */
void vc_deck_strerror(int code, char *buf, int len) {
    const char *s = strerror(code);
    size_t n = strlen(s);
    if (len <= 0) return;
    if (n > (size_t)len - 1) n = (size_t)len - 1;
    memcpy(buf, s, n);
    buf[n] = '\0';
}
