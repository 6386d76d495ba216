/* HDF5 through a table of function pointers filled on first use
 * (hdf5_api.c), so that a command that writes no HDF5 file never loads it:
 * Debian's libhdf5 pulls in some 36 libraries (curl, krb5, gnutls ...)
 * that every start-up would otherwise pay for.
 *
 * h5.c and the tests name the H5* functions as usual: the macros below
 * turn them into calls through the table.  Types and constants come from
 * <hdf5.h> (libhdf5-dev, needed at build time, not linked).  HDF5's
 * predefined types and property classes are global variables
 * (H5T_NATIVE_DOUBLE is `(H5open(), H5T_NATIVE_DOUBLE_g)`): they are
 * resolved too, and read through HL_H5T_* / HL_H5P_* after loading (which
 * calls H5open).  A name missing from the table fails at link time with an
 * undefined H5* reference: add one X(...) line and one #define. */
#ifndef HAMLIE_REPORT_HDF5_API_H
#define HAMLIE_REPORT_HDF5_API_H

#include <hdf5.h>

#include "hamlie/error.h"

/* hdf5.h's flags call H5check_version, which aborts the process when the
 * library loaded is not the version of the headers: the values alone
 * (the same in every HDF5 since 1.8), so $HAMLIE_HDF5_LIB may name a newer
 * one. */
#undef H5F_ACC_RDONLY
#undef H5F_ACC_TRUNC
#define H5F_ACC_RDONLY 0x0000u
#define H5F_ACC_TRUNC 0x0002u

#define HL_HDF5_FUNCTIONS(X)                                                                       \
    X(H5open)                                                                                      \
    X(H5free_memory)                                                                               \
    X(H5Eset_auto2)                                                                                \
    X(H5Pcreate)                                                                                   \
    X(H5Pclose)                                                                                    \
    X(H5Pset_obj_track_times)                                                                      \
    X(H5Pset_file_locking)                                                                         \
    X(H5Fcreate)                                                                                   \
    X(H5Fopen)                                                                                     \
    X(H5Fclose)                                                                                    \
    X(H5Gcreate2)                                                                                  \
    X(H5Gclose)                                                                                    \
    X(H5Oopen)                                                                                     \
    X(H5Oclose)                                                                                    \
    X(H5Screate)                                                                                   \
    X(H5Screate_simple)                                                                            \
    X(H5Sget_simple_extent_ndims)                                                                  \
    X(H5Sget_simple_extent_dims)                                                                   \
    X(H5Sclose)                                                                                    \
    X(H5Tcopy)                                                                                     \
    X(H5Tset_size)                                                                                 \
    X(H5Tset_cset)                                                                                 \
    X(H5Tset_strpad)                                                                               \
    X(H5Tget_size)                                                                                 \
    X(H5Tis_variable_str)                                                                          \
    X(H5Tclose)                                                                                    \
    X(H5Dcreate2)                                                                                  \
    X(H5Dopen2)                                                                                    \
    X(H5Dget_space)                                                                                \
    X(H5Dget_type)                                                                                 \
    X(H5Dwrite)                                                                                    \
    X(H5Dread)                                                                                     \
    X(H5Dclose)                                                                                    \
    X(H5Acreate2)                                                                                  \
    X(H5Aopen)                                                                                     \
    X(H5Aget_space)                                                                                \
    X(H5Aget_type)                                                                                 \
    X(H5Awrite)                                                                                    \
    X(H5Aread)                                                                                     \
    X(H5Aclose)

/* the global variables behind the predefined types and property classes */
#define HL_HDF5_GLOBALS(X)                                                                         \
    X(H5T_NATIVE_DOUBLE_g)                                                                         \
    X(H5T_NATIVE_INT64_g)                                                                          \
    X(H5T_IEEE_F64LE_g)                                                                            \
    X(H5T_STD_I64LE_g)                                                                             \
    X(H5T_C_S1_g)                                                                                  \
    X(H5P_CLS_FILE_CREATE_ID_g)                                                                    \
    X(H5P_CLS_FILE_ACCESS_ID_g)                                                                    \
    X(H5P_CLS_GROUP_CREATE_ID_g)                                                                   \
    X(H5P_CLS_DATASET_CREATE_ID_g)

typedef struct hl_hdf5_api {
#define HL_HDF5_SLOT(name) __typeof__(name) *name;
    HL_HDF5_FUNCTIONS(HL_HDF5_SLOT)
#undef HL_HDF5_SLOT
#define HL_HDF5_GLOBAL_SLOT(name) const hid_t *name;
    HL_HDF5_GLOBALS(HL_HDF5_GLOBAL_SLOT)
#undef HL_HDF5_GLOBAL_SLOT
} hl_hdf5_api;

extern hl_hdf5_api hl_hdf5;

/* Load HDF5 once per process: $HAMLIE_HDF5_LIB if set (tests set a
 * missing one), else libhdf5_serial.so.103, else the file CMake found.
 * HL_OK when every name of the tables was found and H5open succeeded
 * (HDF5's printing of its error stack is then switched off: hamlie reports
 * errors itself), else HL_EUNSUP ("libhdf5_serial.so.103 not found:
 * install libhdf5-103-1 ..."), the same on every later call. */
hl_status hl_hdf5_load(hl_error *err);

#define HL_H5T_NATIVE_DOUBLE (*hl_hdf5.H5T_NATIVE_DOUBLE_g)
#define HL_H5T_NATIVE_INT64 (*hl_hdf5.H5T_NATIVE_INT64_g)
#define HL_H5T_IEEE_F64LE (*hl_hdf5.H5T_IEEE_F64LE_g)
#define HL_H5T_STD_I64LE (*hl_hdf5.H5T_STD_I64LE_g)
#define HL_H5T_C_S1 (*hl_hdf5.H5T_C_S1_g)
#define HL_H5P_FILE_CREATE (*hl_hdf5.H5P_CLS_FILE_CREATE_ID_g)
#define HL_H5P_FILE_ACCESS (*hl_hdf5.H5P_CLS_FILE_ACCESS_ID_g)
#define HL_H5P_GROUP_CREATE (*hl_hdf5.H5P_CLS_GROUP_CREATE_ID_g)
#define HL_H5P_DATASET_CREATE (*hl_hdf5.H5P_CLS_DATASET_CREATE_ID_g)

#ifndef HL_HDF5_API_IMPL
#define H5open (hl_hdf5.H5open)
#define H5free_memory (hl_hdf5.H5free_memory)
#define H5Eset_auto2 (hl_hdf5.H5Eset_auto2)
#define H5Pcreate (hl_hdf5.H5Pcreate)
#define H5Pclose (hl_hdf5.H5Pclose)
#define H5Pset_obj_track_times (hl_hdf5.H5Pset_obj_track_times)
#define H5Pset_file_locking (hl_hdf5.H5Pset_file_locking)
#define H5Fcreate (hl_hdf5.H5Fcreate)
#define H5Fopen (hl_hdf5.H5Fopen)
#define H5Fclose (hl_hdf5.H5Fclose)
#define H5Gcreate2 (hl_hdf5.H5Gcreate2)
#define H5Gclose (hl_hdf5.H5Gclose)
#define H5Oopen (hl_hdf5.H5Oopen)
#define H5Oclose (hl_hdf5.H5Oclose)
#define H5Screate (hl_hdf5.H5Screate)
#define H5Screate_simple (hl_hdf5.H5Screate_simple)
#define H5Sget_simple_extent_ndims (hl_hdf5.H5Sget_simple_extent_ndims)
#define H5Sget_simple_extent_dims (hl_hdf5.H5Sget_simple_extent_dims)
#define H5Sclose (hl_hdf5.H5Sclose)
#define H5Tcopy (hl_hdf5.H5Tcopy)
#define H5Tset_size (hl_hdf5.H5Tset_size)
#define H5Tset_cset (hl_hdf5.H5Tset_cset)
#define H5Tset_strpad (hl_hdf5.H5Tset_strpad)
#define H5Tget_size (hl_hdf5.H5Tget_size)
#define H5Tis_variable_str (hl_hdf5.H5Tis_variable_str)
#define H5Tclose (hl_hdf5.H5Tclose)
#define H5Dcreate2 (hl_hdf5.H5Dcreate2)
#define H5Dopen2 (hl_hdf5.H5Dopen2)
#define H5Dget_space (hl_hdf5.H5Dget_space)
#define H5Dget_type (hl_hdf5.H5Dget_type)
#define H5Dwrite (hl_hdf5.H5Dwrite)
#define H5Dread (hl_hdf5.H5Dread)
#define H5Dclose (hl_hdf5.H5Dclose)
#define H5Acreate2 (hl_hdf5.H5Acreate2)
#define H5Aopen (hl_hdf5.H5Aopen)
#define H5Aget_space (hl_hdf5.H5Aget_space)
#define H5Aget_type (hl_hdf5.H5Aget_type)
#define H5Awrite (hl_hdf5.H5Awrite)
#define H5Aread (hl_hdf5.H5Aread)
#define H5Aclose (hl_hdf5.H5Aclose)
#endif

#endif
