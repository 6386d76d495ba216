/* The journal of a sweep (sweep.h): every result appended as it completes
 * and flushed, so an interrupted sweep resumes from what was done.
 *
 *   header:  "HLSWJRN1", fingerprint u64, ncols u32, arrays u32
 *   record:  member i64, status i32, reason length u32, ncols doubles,
 *            the reason's bytes, then for each kind of array the sweep
 *            gives (bit k of arrays: sweep.h's HL_SWEEP_TRAJ, _CROSS) its
 *            rows i64 and rows * width doubles, FNV-1a of all the above u64
 *
 * Each record is flushed as it is appended, unless the caller defers the
 * flushes (hl_sweep_journal_defer): MPI's rank 0 takes in a worker's
 * chunk of results at once and flushes once after them, since a flush
 * per record (a system call) was two thirds of its cost per row
 * (docs/sweep-at-scale.md).  A kill then loses at most the records not
 * yet flushed, which --resume runs again.
 *
 * The arrays travel in the journal, so --resume gives them without running
 * a member again (a trajectory may have cost minutes).
 * In the machine's byte order: a journal is for resuming on the machine
 * that wrote it.  A record whose checksum does not match, or that is cut
 * short (the process killed mid-write), ends the journal: it and anything
 * after it are cut off before new records are appended. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/buf.h"
#include "sweep/sweep_impl.h"

#define MAGIC "HLSWJRN1"
#define HEADER_BYTES 24
/* stdio's buffer: a deferred flush writes a chunk's records at once */
#define BUFFER_BYTES (1 << 16)

struct hl_sweep_journal {
    FILE *fp;
    char *path;
    const hl_sweep *sw;
    int ncols;
    hl_buf rec; /* one record being built */
    int failed; /* a write failed: the sweep is told to stop */
    int deferred, pending; /* flushes left to hl_sweep_journal_flush; records not flushed */
};

static uint32_t array_bits(const hl_sweep *sw)
{
    uint32_t bits = 0;
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        bits |= (uint32_t)(sw->has_array[k] != 0) << k;
    return bits;
}

static uint64_t fnv(const unsigned char *p, size_t n)
{
    uint64_t h = 0xCBF29CE484222325ULL;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 0x100000001B3ULL;
    return h;
}

static void header(unsigned char *h, const hl_sweep *sw)
{
    uint32_t ncols = (uint32_t)sw->ncols, arrays = array_bits(sw);
    memcpy(h, MAGIC, 8);
    memcpy(h + 8, &sw->fingerprint, 8);
    memcpy(h + 16, &ncols, 4);
    memcpy(h + 20, &arrays, 4);
}

/* Where a record's arrays are read into (aligned: the journal's bytes are
 * not), grown as needed. */
typedef struct scratch {
    double *row;
    double *v[HL_SWEEP_NARRAYS];
    size_t cap[HL_SWEEP_NARRAYS]; /* doubles */
} scratch;

/* The arrays of a record from p + at (the record's first avail bytes);
 * the new offset, or 0 when the record is torn. */
static size_t parse_arrays(const hl_sweep *sw, const unsigned char *p, size_t at, size_t avail,
                           hl_sweep_result *r, scratch *sc)
{
    size_t width = (size_t)hl_sweep_array_width(sw);
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++) {
        r->nrows[k] = 0;
        r->array[k] = NULL;
        if (!sw->has_array[k])
            continue;
        int64_t rows;
        if (avail < at + 8)
            return 0;
        memcpy(&rows, p + at, 8);
        at += 8;
        if (rows < 0 || (uint64_t)rows > (avail - at) / (8 * width))
            return 0;
        size_t n = (size_t)rows * width;
        if (n > sc->cap[k]) {
            sc->v[k] = hl_xrealloc(sc->v[k], n * sizeof(double));
            sc->cap[k] = n;
        }
        if (n > 0) /* v may still be NULL: memcpy's pointers must not be */
            memcpy(sc->v[k], p + at, 8 * n);
        at += 8 * n;
        r->nrows[k] = (long)rows;
        r->array[k] = sc->v[k];
    }
    return at;
}

/* One record at p (avail bytes) into r; its length, or 0 when it is torn. */
static size_t parse_record(const hl_sweep *sw, const unsigned char *p, size_t avail,
                           hl_sweep_result *r, scratch *sc)
{
    size_t ncols = (size_t)sw->ncols, fixed = 8 + 4 + 4 + 8 * ncols;
    if (avail < fixed + 8)
        return 0;
    int64_t member;
    int32_t status;
    uint32_t rlen;
    memcpy(&member, p, 8);
    memcpy(&status, p + 8, 4);
    memcpy(&rlen, p + 12, 4);
    if (rlen >= HL_SWEEP_REASON || avail < fixed + rlen + 8)
        return 0;
    size_t end = parse_arrays(sw, p, fixed + rlen, avail - 8, r, sc);
    if (end == 0)
        return 0;
    uint64_t sum;
    memcpy(&sum, p + end, 8);
    if (sum != fnv(p, end))
        return 0;
    memcpy(sc->row, p + 16, 8 * ncols);
    r->member = (long)member;
    r->status = (hl_status)status;
    memcpy(r->reason, p + fixed, rlen);
    r->reason[rlen] = '\0';
    r->row = sc->row;
    return end + 8;
}

static hl_status read_file(unsigned char **data, size_t *n, const char *path, hl_error *err)
{
    *data = NULL;
    *n = 0;
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return errno == ENOENT ? HL_OK
                               : hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot read '%s': %s",
                                              path, strerror(errno));
    hl_buf b;
    hl_buf_init(&b);
    int bad = hl_buf_read_stream(&b, fp);
    fclose(fp);
    *n = b.len;
    *data = (unsigned char *)hl_buf_take(&b);
    if (bad)
        return hl_error_set(err, HL_EIO, NULL, -1, 0, "reading '%s' failed", path);
    return HL_OK;
}

/* Fills tab from the journal's data; *good is the length of its sound part. */
static hl_status load(const hl_sweep *sw, const char *path, const unsigned char *data, size_t n,
                      hl_sweep_table *tab, size_t *good, hl_error *err)
{
    unsigned char h[HEADER_BYTES];
    header(h, sw);
    *good = 0;
    if (n < HEADER_BYTES)
        return HL_OK; /* torn in its header: nothing was recorded */
    if (memcmp(data, MAGIC, 8) != 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "'%s' is not a sweep journal", path);
    if (memcmp(data, h, HEADER_BYTES) != 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the journal '%s' is another sweep's (its fingerprint differs): "
                            "remove it to start afresh",
                            path);
    scratch sc;
    memset(&sc, 0, sizeof sc);
    sc.row = hl_xcalloc((size_t)sw->ncols, sizeof *sc.row);
    hl_sweep_result r;
    size_t at = HEADER_BYTES, k;
    while ((k = parse_record(sw, data + at, n - at, &r, &sc)) > 0) {
        if (r.member >= 0 && r.member < sw->count)
            hl_sweep_table_store(&r, tab);
        at += k;
    }
    free(sc.row);
    for (int i = 0; i < HL_SWEEP_NARRAYS; i++)
        free(sc.v[i]);
    *good = at;
    return HL_OK;
}

hl_status hl_sweep_journal_open(hl_sweep_journal **out, const hl_sweep *sw, const char *path,
                                int resume, hl_sweep_table *tab, hl_error *err)
{
    *out = NULL;
    hl_buf name;
    hl_buf_init(&name);
    hl_buf_printf(&name, "%s.journal", path);
    char *jpath = hl_buf_take(&name);
    size_t n = 0, good = 0;
    unsigned char *data = NULL;
    int st = resume ? read_file(&data, &n, jpath, err) : HL_OK;
    if (st == HL_OK && resume)
        st = load(sw, jpath, data, n, tab, &good, err);
    free(data);
    FILE *fp = NULL;
    if (st == HL_OK) { /* the torn tail cut off, then records appended after the sound part */
        fp = fopen(jpath, good > 0 ? "r+b" : "wb");
        if (fp != NULL)
            setvbuf(fp, NULL, _IOFBF, BUFFER_BYTES); /* before any other use of fp */
        if (fp == NULL || (good > 0 && (ftruncate(fileno(fp), (off_t)good) != 0 ||
                                        fseek(fp, (long)good, SEEK_SET) != 0)))
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write the journal '%s': %s", jpath,
                              strerror(errno));
    }
    if (st == HL_OK && good == 0) {
        unsigned char h[HEADER_BYTES];
        header(h, sw);
        if (fwrite(h, 1, HEADER_BYTES, fp) != HEADER_BYTES || fflush(fp) != 0)
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write the journal '%s'", jpath);
    }
    if (st != HL_OK) {
        if (fp != NULL)
            fclose(fp);
        free(jpath);
        return st;
    }
    hl_sweep_journal *j = hl_xcalloc(1, sizeof *j);
    j->fp = fp;
    j->path = jpath;
    j->sw = sw;
    j->ncols = sw->ncols;
    hl_buf_init(&j->rec);
    *out = j;
    return HL_OK;
}

int hl_sweep_journal_append(const hl_sweep_result *r, void *arg)
{
    hl_sweep_journal *j = arg;
    int64_t member = r->member;
    int32_t status = (int32_t)r->status;
    uint32_t rlen = (uint32_t)strnlen(r->reason, HL_SWEEP_REASON - 1);
    hl_buf *b = &j->rec;
    b->len = 0;
    hl_buf_putn(b, (const char *)&member, 8);
    hl_buf_putn(b, (const char *)&status, 4);
    hl_buf_putn(b, (const char *)&rlen, 4);
    hl_buf_putn(b, (const char *)r->row, 8 * (size_t)j->ncols);
    hl_buf_putn(b, r->reason, rlen);
    size_t width = (size_t)hl_sweep_array_width(j->sw);
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        if (j->sw->has_array[k]) {
            int64_t rows = r->array[k] != NULL ? r->nrows[k] : 0;
            hl_buf_putn(b, (const char *)&rows, 8);
            if (rows > 0)
                hl_buf_putn(b, (const char *)r->array[k], 8 * (size_t)rows * width);
        }
    uint64_t sum = fnv((const unsigned char *)b->s, b->len);
    hl_buf_putn(b, (const char *)&sum, 8);
    if (fwrite(b->s, 1, b->len, j->fp) != b->len)
        j->failed = 1;
    j->pending = 1;
    return j->deferred ? j->failed : hl_sweep_journal_flush(j);
}

void hl_sweep_journal_defer(hl_sweep_journal *j)
{
    j->deferred = 1;
}

int hl_sweep_journal_flush(hl_sweep_journal *j)
{
    if (j->pending && !j->failed && fflush(j->fp) != 0)
        j->failed = 1;
    j->pending = 0;
    return j->failed;
}

void hl_sweep_journal_close(hl_sweep_journal *j, int remove_file)
{
    if (j == NULL)
        return;
    fclose(j->fp);
    if (remove_file)
        remove(j->path);
    hl_buf_clear(&j->rec);
    free(j->path);
    free(j);
}

int hl_sweep_journal_failed(const hl_sweep_journal *j)
{
    return j != NULL && j->failed;
}
