/* Thin C layer over libdeflate for vemcontact_output_zlib: a byte string
 * compressed in fixed-size blocks, each block one zlib stream (VTK's
 * vtkZLibDataCompressor layout), by several threads at once.
 *
 * The calling thread and up to threads - 1 helper threads take the next block
 * from a shared counter until none is left, each with its own compressor, and
 * write block k at dst + k * bound; the streams are then moved together in
 * block order.  Every block is compressed alone, so the bytes do not depend on
 * the number of threads or on which thread took which block.  Taking blocks
 * one at a time (not a half each) keeps the caller from waiting on a helper
 * that another process holds off the processor: it waits at most for the
 * block that helper is compressing.  A helper that cannot be started leaves
 * its share to the others.
 *
 * Returns 0, or -1 when a compressor cannot be allocated or a stream does not
 * fit in `bound` bytes (then nothing in dst or sizes is meaningful).
 */
#define _GNU_SOURCE
#include <libdeflate.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdint.h>
#include <string.h>

enum { max_threads = 8 };

struct blocks_job {
    const char *src;
    int64_t nbytes, block, nblocks, bound;
    char *dst;
    int64_t *sizes;
    int level;
    atomic_llong next;
    atomic_int failed;
};

static void *compress_some(void *arg)
{
    struct blocks_job *job = arg;
    struct libdeflate_compressor *c = libdeflate_alloc_compressor(job->level);
    if (c == NULL) {
        atomic_store(&job->failed, 1);
        return NULL;
    }
    for (;;) {
        long long k = atomic_fetch_add(&job->next, 1);
        if (k >= job->nblocks || atomic_load(&job->failed)) break;
        int64_t first = k * job->block;
        int64_t len = job->nbytes - first < job->block ? job->nbytes - first : job->block;
        size_t n = libdeflate_zlib_compress(c, job->src + first, (size_t)len,
                                            job->dst + k * job->bound, (size_t)job->bound);
        if (n == 0) atomic_store(&job->failed, 1);
        job->sizes[k] = (int64_t)n;
    }
    libdeflate_free_compressor(c);
    return NULL;
}

/* Processors this process may run on (its affinity mask), at least 1. */
int vc_deflate_processors(void)
{
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
    int n = CPU_COUNT(&set);
    return n > 0 ? n : 1;
}

/* Largest zlib stream of `nbytes` bytes at any level. */
int64_t vc_deflate_bound(int64_t nbytes)
{
    return (int64_t)libdeflate_zlib_compress_bound(NULL, (size_t)nbytes);
}

/* Compress src(1:nbytes) in blocks of `block` bytes at `level` with up to
 * `threads` threads.  dst holds nblocks * bound bytes with bound =
 * vc_deflate_bound(block); on return the streams are dst(1:*total), block k's
 * size in sizes[k]. */
int vc_deflate_blocks(const char *src, int64_t nbytes, int64_t block, int level, int threads,
                      char *dst, int64_t bound, int64_t *sizes, int64_t *total)
{
    struct blocks_job job = {.src = src, .nbytes = nbytes, .block = block, .bound = bound,
                             .dst = dst, .sizes = sizes, .level = level};
    pthread_t helper[max_threads];
    int started = 0;

    *total = 0;
    if (block <= 0) return -1;
    job.nblocks = (nbytes + block - 1) / block;
    atomic_init(&job.next, 0);
    atomic_init(&job.failed, 0);
    if (threads > max_threads) threads = max_threads;
    if (threads > job.nblocks) threads = (int)job.nblocks;
    for (int t = 1; t < threads; t++) {
        if (pthread_create(&helper[started], NULL, compress_some, &job) != 0) break;
        started++;
    }
    compress_some(&job);
    for (int t = 0; t < started; t++) pthread_join(helper[t], NULL);
    if (atomic_load(&job.failed)) return -1;
    /* block k starts at k * bound >= the sum of the sizes before it */
    int64_t pos = 0;
    for (int64_t k = 0; k < job.nblocks; k++) {
        if (pos != k * bound) memmove(dst + pos, dst + k * bound, (size_t)sizes[k]);
        pos += sizes[k];
    }
    *total = pos;
    return 0;
}
