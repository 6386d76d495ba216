/* The HDF5 writer of h5.h: a file under a temporary name, objects written
 * in the order of the calls with no times recorded (so the same calls give
 * the same bytes), renamed into place by the commit.  The library is
 * reached through the table of hdf5_api.h. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/h5.h"
#include "report/hdf5_api.h"

struct hl_h5 {
    hid_t file;
    char *path, *tmp;
    hl_error first; /* the first failure: every later call repeats it */
};

hl_status hl_h5_available(hl_error *err)
{
    return hl_hdf5_load(err);
}

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), k = strlen(tail);
    return n > k && strcmp(s + n - k, tail) == 0;
}

int hl_h5_is_h5_path(const char *path)
{
    return path != NULL && (ends_with(path, ".h5") || ends_with(path, ".hdf5"));
}

/* The sticky status: HL_OK, or the first failure copied to err. */
static hl_status failed(const hl_h5 *f, hl_error *err)
{
    if (f->first.status != HL_OK && err != NULL)
        *err = f->first;
    return f->first.status;
}

/* Records the first failure (about object `what`) and returns it. */
static hl_status fail(hl_h5 *f, hl_error *err, const char *what)
{
    if (f->first.status == HL_OK)
        hl_error_set(&f->first, HL_EIO, NULL, -1, 0, "cannot write %s to '%s' (HDF5)", what,
                     f->path);
    return failed(f, err);
}

/* A property list of class cls that records no times (the root group's
 * file-creation list, groups', datasets'), or a negative id. */
static hid_t timeless(hid_t cls)
{
    hid_t pl = H5Pcreate(cls);
    if (pl >= 0 && H5Pset_obj_track_times(pl, 0) < 0) {
        H5Pclose(pl);
        return -1;
    }
    return pl;
}

/* The file under tmp; HDF5's file locking off (the name is ours alone, and
 * locking fails on some cluster file systems).  errno says why on failure. */
static hid_t create_file(const char *tmp)
{
    hid_t fcpl = timeless(HL_H5P_FILE_CREATE), fapl = H5Pcreate(HL_H5P_FILE_ACCESS);
    hid_t file = -1;
    if (fcpl >= 0 && fapl >= 0 && H5Pset_file_locking(fapl, 0, 1) >= 0) {
        errno = 0;
        file = H5Fcreate(tmp, H5F_ACC_TRUNC, fcpl, fapl);
    }
    int saved = errno;
    if (fcpl >= 0)
        H5Pclose(fcpl);
    if (fapl >= 0)
        H5Pclose(fapl);
    errno = saved;
    return file;
}

hl_status hl_h5_create(hl_h5 **out, const char *path, hl_error *err)
{
    *out = NULL;
    hl_status st = hl_hdf5_load(err);
    if (st != HL_OK)
        return st;
    size_t n = strlen(path) + 5;
    char *tmp = hl_xmalloc(n);
    snprintf(tmp, n, "%s.tmp", path);
    hid_t file = create_file(tmp);
    if (file < 0) {
        int why = errno;
        remove(tmp); /* HDF5 may have made it before failing */
        free(tmp);
        return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", path,
                            why != 0 ? strerror(why) : "HDF5 could not create it");
    }
    hl_h5 *f = hl_xcalloc(1, sizeof *f);
    f->file = file;
    f->path = hl_xstrdup(path);
    f->tmp = tmp;
    hl_error_clear(&f->first);
    *out = f;
    return HL_OK;
}

static void release(hl_h5 *f)
{
    free(f->path);
    free(f->tmp);
    free(f);
}

void hl_h5_abort(hl_h5 *f)
{
    if (f == NULL)
        return;
    H5Fclose(f->file);
    remove(f->tmp);
    release(f);
}

hl_status hl_h5_commit(hl_h5 *f, hl_error *err)
{
    hl_status st = failed(f, err);
    if (st != HL_OK) {
        hl_h5_abort(f);
        return st;
    }
    if (H5Fclose(f->file) < 0) {
        st = hl_error_set(err, HL_EIO, NULL, -1, 0, "writing '%s' failed (HDF5 close)", f->path);
        remove(f->tmp);
    } else if (rename(f->tmp, f->path) != 0) {
        st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", f->path,
                          strerror(errno));
        remove(f->tmp);
    }
    release(f);
    return st;
}

hl_status hl_h5_group(hl_h5 *f, const char *name, hl_error *err)
{
    if (failed(f, err) != HL_OK)
        return f->first.status;
    hid_t gcpl = timeless(HL_H5P_GROUP_CREATE);
    hid_t g = gcpl < 0 ? -1 : H5Gcreate2(f->file, name, H5P_DEFAULT, gcpl, H5P_DEFAULT);
    if (gcpl >= 0)
        H5Pclose(gcpl);
    if (g < 0) {
        char what[300];
        snprintf(what, sizeof what, "group '%s'", name);
        return fail(f, err, what);
    }
    H5Gclose(g);
    return HL_OK;
}

/* ---- attributes --------------------------------------------------------- */

/* The attribute obj.name of type ftype over space, written from buf of
 * type mtype.  Closes space. */
static hl_status put_attr(hl_h5 *f, const char *obj, const char *name, hid_t ftype, hid_t mtype,
                          hid_t space, const void *buf, hl_error *err)
{
    if (failed(f, err) != HL_OK) {
        H5Sclose(space);
        return f->first.status;
    }
    hid_t o = H5Oopen(f->file, obj != NULL ? obj : "/", H5P_DEFAULT);
    hid_t a = o < 0 ? -1 : H5Acreate2(o, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT);
    int ok = a >= 0 && H5Awrite(a, mtype, buf) >= 0;
    if (a >= 0)
        H5Aclose(a);
    if (o >= 0)
        H5Oclose(o);
    H5Sclose(space);
    if (ok)
        return HL_OK;
    char what[300];
    snprintf(what, sizeof what, "attribute '%s' of '%s'", name, obj != NULL ? obj : "/");
    return fail(f, err, what);
}

/* The variable-length UTF-8 string type (caller closes it). */
static hid_t vlen_string(void)
{
    hid_t t = H5Tcopy(HL_H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    return t;
}

hl_status hl_h5_attr_string(hl_h5 *f, const char *obj, const char *name, const char *value,
                            hl_error *err)
{
    const char *v = value != NULL ? value : "";
    hid_t t = vlen_string();
    hl_status st = put_attr(f, obj, name, t, t, H5Screate(H5S_SCALAR), &v, err);
    H5Tclose(t);
    return st;
}

hl_status hl_h5_attr_double(hl_h5 *f, const char *obj, const char *name, double value,
                            hl_error *err)
{
    return put_attr(f, obj, name, HL_H5T_IEEE_F64LE, HL_H5T_NATIVE_DOUBLE, H5Screate(H5S_SCALAR),
                    &value, err);
}

hl_status hl_h5_attr_long(hl_h5 *f, const char *obj, const char *name, long value, hl_error *err)
{
    int64_t v = value;
    return put_attr(f, obj, name, HL_H5T_STD_I64LE, HL_H5T_NATIVE_INT64, H5Screate(H5S_SCALAR), &v,
                    err);
}

/* NULL strings as "", in a copy of the array of pointers */
static const char **no_nulls(const char *const *v, long n)
{
    const char **s = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *s);
    for (long i = 0; i < n; i++)
        s[i] = v[i] != NULL ? v[i] : "";
    return s;
}

hl_status hl_h5_attr_strings(hl_h5 *f, const char *obj, const char *name, const char *const *values,
                             long n, hl_error *err)
{
    hsize_t dim = (hsize_t)n;
    const char **s = no_nulls(values, n);
    hid_t t = vlen_string();
    hl_status st = put_attr(f, obj, name, t, t, H5Screate_simple(1, &dim, NULL), s, err);
    H5Tclose(t);
    free(s);
    return st;
}

/* ---- datasets ----------------------------------------------------------- */

/* The dataset name (rank 1 or 2, dims) of type ftype, written from buf of
 * type mtype (nothing to write when it is empty). */
static hl_status put_dataset(hl_h5 *f, const char *name, hid_t ftype, hid_t mtype, int rank,
                             const hsize_t *dims, const void *buf, hl_error *err)
{
    if (failed(f, err) != HL_OK)
        return f->first.status;
    hsize_t count = rank == 1 ? dims[0] : dims[0] * dims[1];
    hid_t space = H5Screate_simple(rank, dims, NULL), dcpl = timeless(HL_H5P_DATASET_CREATE);
    hid_t d = space < 0 || dcpl < 0
                  ? -1
                  : H5Dcreate2(f->file, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    int ok = d >= 0 && (count == 0 || H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
    if (d >= 0)
        H5Dclose(d);
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (space >= 0)
        H5Sclose(space);
    if (ok)
        return HL_OK;
    char what[300];
    snprintf(what, sizeof what, "dataset '%s'", name);
    return fail(f, err, what);
}

hl_status hl_h5_doubles(hl_h5 *f, const char *name, const double *v, long n, long stride,
                        hl_error *err)
{
    hsize_t dim = (hsize_t)n;
    if (stride == 1)
        return put_dataset(f, name, HL_H5T_IEEE_F64LE, HL_H5T_NATIVE_DOUBLE, 1, &dim, v, err);
    double *col = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *col);
    for (long i = 0; i < n; i++)
        col[i] = v[i * stride];
    hl_status st = put_dataset(f, name, HL_H5T_IEEE_F64LE, HL_H5T_NATIVE_DOUBLE, 1, &dim, col, err);
    free(col);
    return st;
}

hl_status hl_h5_int64s(hl_h5 *f, const char *name, const int64_t *v, long n, hl_error *err)
{
    hsize_t dim = (hsize_t)n;
    return put_dataset(f, name, HL_H5T_STD_I64LE, HL_H5T_NATIVE_INT64, 1, &dim, v, err);
}

hl_status hl_h5_matrix(hl_h5 *f, const char *name, const double *v, long rows, long cols,
                       hl_error *err)
{
    hsize_t dims[2] = {(hsize_t)rows, (hsize_t)cols};
    return put_dataset(f, name, HL_H5T_IEEE_F64LE, HL_H5T_NATIVE_DOUBLE, 2, dims, v, err);
}

/* Fixed-length strings: the longest plus its terminator, zero-padded
 * (so the unused bytes are zeros, not whatever memory held). */
static hl_status put_fixed_strings(hl_h5 *f, const char *name, const char **s, long n,
                                   hl_error *err)
{
    size_t width = 1;
    for (long i = 0; i < n; i++)
        if (strlen(s[i]) + 1 > width)
            width = strlen(s[i]) + 1;
    char *packed = hl_xcalloc((size_t)(n > 0 ? n : 1), width);
    for (long i = 0; i < n; i++)
        memcpy(packed + (size_t)i * width, s[i], strlen(s[i]));
    hid_t t = H5Tcopy(HL_H5T_C_S1);
    H5Tset_size(t, width);
    H5Tset_strpad(t, H5T_STR_NULLTERM);
    H5Tset_cset(t, H5T_CSET_UTF8);
    hsize_t dim = (hsize_t)n;
    hl_status st = put_dataset(f, name, t, t, 1, &dim, packed, err);
    H5Tclose(t);
    free(packed);
    return st;
}

hl_status hl_h5_strings(hl_h5 *f, const char *name, const char *const *v, long n, int fixed,
                        hl_error *err)
{
    if (failed(f, err) != HL_OK)
        return f->first.status;
    const char **s = no_nulls(v, n);
    hl_status st;
    if (fixed) {
        st = put_fixed_strings(f, name, s, n, err);
    } else {
        hid_t t = vlen_string();
        hsize_t dim = (hsize_t)n;
        st = put_dataset(f, name, t, t, 1, &dim, s, err);
        H5Tclose(t);
    }
    free(s);
    return st;
}
