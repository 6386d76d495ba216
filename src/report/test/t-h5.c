/* The HDF5 writer (h5.h): what is written reads back the same through the
 * HDF5 library itself (values, attributes, strings of both kinds, shapes);
 * the same calls give the same bytes; a failure leaves no file at all. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hamlie/h5.h"
#include "hl_test.h"
#include "report/hdf5_api.h"

static char dir[64];

static const char *in_dir(const char *name)
{
    static char path[4][128];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", dir, name);
    return path[k];
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* values that survive only an exact round trip: not decimal, signed zero, huge */
static const double table[4][3] = {
    {0.1, -0.0, 1e300}, {1.0 / 3, 2.5, -7e-310}, {3.0, 4.0, 5.0}, {6.0, 7.0, 8.0}};
static const int64_t ints[3] = {-1, 0, INT64_C(9007199254740993)};
static const char *const words[3] = {"ok", "", "newton failed at step 12 (\u00e9)"};

static hl_status write_sample(const char *path, hl_error *err)
{
    hl_h5 *f;
    hl_status st = hl_h5_create(&f, path, err);
    if (st != HL_OK)
        return st;
    hl_h5_attr_string(f, NULL, "H", "p^2/2 - cos(q)", err);
    hl_h5_attr_double(f, "/", "t", 0.1, err);
    hl_h5_attr_long(f, NULL, "members", -42, err);
    hl_h5_attr_strings(f, NULL, "columns", words, 3, err);
    hl_h5_group(f, "summary", err);
    hl_h5_doubles(f, "summary/all", &table[0][0], 12, 1, err);
    hl_h5_doubles(f, "summary/col1", &table[0][1], 4, 3, err); /* a column */
    hl_h5_doubles(f, "summary/none", NULL, 0, 1, err);
    hl_h5_int64s(f, "summary/ints", ints, 3, err);
    hl_h5_strings(f, "summary/vlen", words, 3, 0, err);
    hl_h5_strings(f, "summary/fixed", words, 3, 1, err);
    hl_h5_matrix(f, "matrix", &table[0][0], 4, 3, err);
    hl_h5_attr_string(f, "summary/col1", "unit", "1", err);
    return hl_h5_commit(f, err);
}

/* n elements of dataset name, read as mtype into buf; its dims in dims */
static int read_dataset(hid_t file, const char *name, hid_t mtype, void *buf, hsize_t dims[2])
{
    hid_t d = H5Dopen2(file, name, H5P_DEFAULT);
    if (d < 0)
        return -1;
    hid_t sp = H5Dget_space(d);
    dims[0] = dims[1] = 0;
    int rank = H5Sget_simple_extent_ndims(sp);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    H5Sclose(sp);
    int rc =
        (dims[0] == 0 || H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0) ? rank : -1;
    H5Dclose(d);
    return rc;
}

static void check_numbers(hid_t file)
{
    double v[12];
    hsize_t dims[2];
    CHECK(read_dataset(file, "summary/all", HL_H5T_NATIVE_DOUBLE, v, dims) == 1 && dims[0] == 12);
    CHECK(memcmp(v, table, sizeof table) == 0); /* bit for bit, -0.0 and subnormals too */
    CHECK(read_dataset(file, "summary/col1", HL_H5T_NATIVE_DOUBLE, v, dims) == 1 && dims[0] == 4);
    for (int i = 0; i < 4; i++)
        CHECK_MSG(memcmp(&v[i], &table[i][1], sizeof v[i]) == 0, "col1[%d] = %g", i, v[i]);
    CHECK(read_dataset(file, "summary/none", HL_H5T_NATIVE_DOUBLE, v, dims) == 1 && dims[0] == 0);
    int64_t k[3];
    CHECK(read_dataset(file, "summary/ints", HL_H5T_NATIVE_INT64, k, dims) == 1 && dims[0] == 3);
    CHECK(memcmp(k, ints, sizeof k) == 0);
    CHECK(read_dataset(file, "matrix", HL_H5T_NATIVE_DOUBLE, v, dims) == 2 && dims[0] == 4 &&
          dims[1] == 3);
    CHECK(memcmp(v, table, sizeof table) == 0);
}

static void check_strings(hid_t file)
{
    hsize_t dims[2];
    char *s[3] = {NULL, NULL, NULL};
    hid_t d = H5Dopen2(file, "summary/vlen", H5P_DEFAULT);
    hid_t t = H5Dget_type(d);
    CHECK(H5Tis_variable_str(t) > 0);
    CHECK(read_dataset(file, "summary/vlen", t, s, dims) == 1 && dims[0] == 3);
    for (int i = 0; i < 3; i++) {
        CHECK_MSG(s[i] != NULL && strcmp(s[i], words[i]) == 0, "vlen[%d]", i);
        H5free_memory(s[i]);
    }
    H5Tclose(t);
    H5Dclose(d);
    d = H5Dopen2(file, "summary/fixed", H5P_DEFAULT);
    t = H5Dget_type(d);
    size_t width = H5Tget_size(t);
    CHECK_MSG(H5Tis_variable_str(t) == 0 && width == strlen(words[2]) + 1, "width %zu", width);
    char packed[3 * 64];
    CHECK(width <= 64 && read_dataset(file, "summary/fixed", t, packed, dims) == 1);
    for (int i = 0; i < 3; i++)
        CHECK_STR(packed + (size_t)i * width, words[i]);
    H5Tclose(t);
    H5Dclose(d);
}

static void check_attributes(hid_t file)
{
    hid_t root = H5Oopen(file, "/", H5P_DEFAULT);
    hid_t a = H5Aopen(root, "t", H5P_DEFAULT);
    double t = 0;
    CHECK(a >= 0 && H5Aread(a, HL_H5T_NATIVE_DOUBLE, &t) >= 0 && t == 0.1);
    H5Aclose(a);
    a = H5Aopen(root, "members", H5P_DEFAULT);
    int64_t m = 0;
    CHECK(a >= 0 && H5Aread(a, HL_H5T_NATIVE_INT64, &m) >= 0 && m == -42);
    H5Aclose(a);
    a = H5Aopen(root, "H", H5P_DEFAULT);
    hid_t ty = H5Aget_type(a);
    char *h = NULL;
    CHECK(a >= 0 && H5Aread(a, ty, &h) >= 0 && h != NULL && strcmp(h, "p^2/2 - cos(q)") == 0);
    H5free_memory(h);
    H5Tclose(ty);
    H5Aclose(a);
    H5Oclose(root);
}

static void test_round_trip(void)
{
    hl_error err;
    hl_error_clear(&err);
    const char *path = in_dir("a.h5");
    CHECK_MSG(write_sample(path, &err) == HL_OK, "%s", err.msg);
    CHECK(!exists(in_dir("a.h5.tmp")));
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK(file >= 0);
    if (file < 0)
        return;
    check_numbers(file);
    check_strings(file);
    check_attributes(file);
    H5Fclose(file);
}

static char *slurp(const char *path, long *n)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    fseek(fp, 0, SEEK_END);
    *n = ftell(fp);
    rewind(fp);
    char *b = malloc((size_t)*n + 1);
    if (fread(b, 1, (size_t)*n, fp) != (size_t)*n)
        *n = -1;
    fclose(fp);
    return b;
}

/* the same calls, a second file: the same bytes (no times, no addresses
 * of this process's memory) */
static void test_same_bytes(void)
{
    hl_error err;
    CHECK(write_sample(in_dir("b.h5"), &err) == HL_OK);
    long na = 0, nb = 0;
    char *a = slurp(in_dir("a.h5"), &na), *b = slurp(in_dir("b.h5"), &nb);
    CHECK_MSG(a != NULL && b != NULL && na > 0 && na == nb && memcmp(a, b, (size_t)na) == 0,
              "a.h5 (%ld bytes) and b.h5 (%ld bytes) differ", na, nb);
    free(a);
    free(b);
}

static void test_failures(void)
{
    hl_error err;
    hl_error_clear(&err);
    hl_h5 *f = (hl_h5 *)1;
    const char *nowhere = in_dir("no-such-folder/x.h5");
    CHECK(hl_h5_create(&f, nowhere, &err) == HL_EIO && f == NULL);
    CHECK_MSG(strstr(err.msg, "no-such-folder/x.h5") != NULL, "%s", err.msg);
    /* a failure in the middle: every later call repeats it; nothing is left */
    const char *path = in_dir("c.h5");
    CHECK(hl_h5_create(&f, path, &err) == HL_OK);
    CHECK(hl_h5_doubles(f, "missing-group/x", &table[0][0], 3, 1, &err) == HL_EIO);
    CHECK_MSG(strstr(err.msg, "dataset 'missing-group/x'") != NULL, "%s", err.msg);
    hl_error later;
    hl_error_clear(&later);
    CHECK(hl_h5_group(f, "fine", &later) == HL_EIO && strcmp(later.msg, err.msg) == 0);
    CHECK(hl_h5_attr_double(f, NULL, "x", 1, &later) == HL_EIO);
    CHECK(hl_h5_commit(f, &later) == HL_EIO && strcmp(later.msg, err.msg) == 0);
    CHECK(!exists(path) && !exists(in_dir("c.h5.tmp")));
    /* the same name twice is HDF5's refusal, reported */
    CHECK(hl_h5_create(&f, path, &err) == HL_OK);
    CHECK(hl_h5_group(f, "g", &err) == HL_OK);
    CHECK(hl_h5_group(f, "g", &err) == HL_EIO);
    hl_h5_commit(f, &err);
    CHECK(!exists(path) && !exists(in_dir("c.h5.tmp")));
    /* abort leaves nothing */
    CHECK(hl_h5_create(&f, path, &err) == HL_OK);
    CHECK(hl_h5_group(f, "g", &err) == HL_OK);
    hl_h5_abort(f);
    CHECK(!exists(path) && !exists(in_dir("c.h5.tmp")));
    hl_h5_abort(NULL);
}

static void test_names(void)
{
    CHECK(hl_h5_is_h5_path("out.h5") && hl_h5_is_h5_path("a/b.hdf5"));
    CHECK(!hl_h5_is_h5_path("out.csv") && !hl_h5_is_h5_path(".h5") && !hl_h5_is_h5_path("h5"));
    CHECK(!hl_h5_is_h5_path(NULL) && !hl_h5_is_h5_path("-"));
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/hamlie-t-h5-XXXXXX");
    if (mkdtemp(dir) == NULL)
        return 2;
    hl_error err;
    if (hl_h5_available(&err) != HL_OK) {
        fprintf(stderr, "libhdf5 not loadable: %s\n", err.msg);
        return 1;
    }
    test_names();
    test_round_trip();
    test_same_bytes();
    test_failures();
    const char *files[] = {"a.h5", "b.h5"};
    for (int i = 0; i < 2; i++)
        remove(in_dir(files[i]));
    rmdir(dir);
    return HL_TEST_END();
}
