/* hamlie — a small HDF5 writer for the result files of sections and sweeps
 * (readable with h5py: f["summary/max_dH"][:], f.attrs["scheme"]).
 *
 *   hl_h5 *f;
 *   if (hl_h5_create(&f, "out.h5", err) != HL_OK) return ...;
 *   hl_h5_attr_string(f, NULL, "H", "p^2/2 - cos(q)", err);   // on the root
 *   hl_h5_group(f, "summary", err);
 *   hl_h5_doubles(f, "summary/max_dH", rows + 7, n, ncols, err);  // a column
 *   return hl_h5_commit(f, err);           // or hl_h5_abort(f) on the way out
 *
 * Nothing half-written: the file is made under a temporary name beside
 * path (path + ".tmp"); hl_h5_commit closes it and renames it to path,
 * hl_h5_abort (and a failed commit) closes and removes it.  Errors are
 * sticky: after the first failure every call returns that status (err
 * refilled with the first message) and does nothing, so a writer may check
 * once, at the commit.
 *
 * The same calls with the same data give the same bytes: no object records
 * its times (H5Pset_obj_track_times off for the root, groups and
 * datasets), and objects are laid out in the order of the calls.  Numbers
 * are stored little-endian (IEEE f64, i64) whatever the machine; strings
 * are UTF-8, variable-length (h5py gives str for attributes, bytes for
 * datasets unless .asstr()) or fixed-length (null-terminated, the longest
 * plus one).
 *
 * libhdf5 is loaded on the first call (report/hdf5_api.c; $HAMLIE_HDF5_LIB
 * names another file); without it every call is HL_EUNSUP with the reason.
 * Object names are paths from the root ("summary/max_dH"); a group must be
 * made before what goes in it.  One writer is used by one thread at a
 * time (the Debian library is not thread-safe: one file at a time).
 */
#ifndef HAMLIE_H5_H
#define HAMLIE_H5_H

#include <stdint.h>

#include "hamlie/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_h5 hl_h5;

/* HL_OK when libhdf5 can be loaded, else HL_EUNSUP with the reason: a
 * command asked for an .h5 file calls it before computing anything. */
hl_status hl_h5_available(hl_error *err);

/* 1 when path names an HDF5 file (ends in ".h5" or ".hdf5"), else 0. */
int hl_h5_is_h5_path(const char *path);

/* HL_EIO naming the file when it cannot be made (a missing folder, no
 * permission); *out NULL then. */
hl_status hl_h5_create(hl_h5 **out, const char *path, hl_error *err);
/* Closes, renames to path and frees f (always, even on failure, which
 * removes the temporary file and returns the first error). */
hl_status hl_h5_commit(hl_h5 *f, hl_error *err);
/* Closes, removes the temporary file and frees f.  NULL is a no-op. */
void hl_h5_abort(hl_h5 *f);

/* A group ("summary"; "a/b" inside an existing a). */
hl_status hl_h5_group(hl_h5 *f, const char *name, hl_error *err);

/* Attributes (scalars, or a 1-D list of strings) of the object obj: NULL
 * or "/" the root, else a group or dataset made before. */
hl_status hl_h5_attr_string(hl_h5 *f, const char *obj, const char *name, const char *value,
                            hl_error *err);
hl_status hl_h5_attr_double(hl_h5 *f, const char *obj, const char *name, double value,
                            hl_error *err);
hl_status hl_h5_attr_long(hl_h5 *f, const char *obj, const char *name, long value, hl_error *err);
hl_status hl_h5_attr_strings(hl_h5 *f, const char *obj, const char *name, const char *const *values,
                             long n, hl_error *err);

/* 1-D datasets of n values (n may be 0).  doubles takes every stride-th
 * value from v (stride 1: contiguous; ncols: one column of a row-major
 * table); int64s and strings are contiguous (a NULL string is stored as
 * ""). */
hl_status hl_h5_doubles(hl_h5 *f, const char *name, const double *v, long n, long stride,
                        hl_error *err);
hl_status hl_h5_int64s(hl_h5 *f, const char *name, const int64_t *v, long n, hl_error *err);
hl_status hl_h5_strings(hl_h5 *f, const char *name, const char *const *v, long n, int fixed,
                        hl_error *err);
/* A 2-D dataset rows x cols of doubles, row-major (h5py: shape (rows, cols)). */
hl_status hl_h5_matrix(hl_h5 *f, const char *name, const double *v, long rows, long cols,
                       hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
