/* Fuzz target for maps ("X = x + D*p; P = p - D*X"): `canonical --map`
 * reads one with hl_system_read_map, `errors`/`run --map` with
 * hl_scheme_from_map.  Any input must be read or refused cleanly, on a
 * system with one degree of freedom and on one with two and a parameter. */
#include "fuzz.h"
#include "hamlie/alg.h"
#include "hamlie/ham.h"
#include "hamlie/scheme.h"

static void read_map(const char *H, const char *map)
{
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    hl_system *sys;
    hl_error err;
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        abort(); /* the fixed systems are valid */
    int n2 = 2 * hl_system_ndof(sys);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg images[4];
    for (int i = 0; i < n2; i++)
        hl_alg_init(&images[i], ctx);
    fuzz_check_error(hl_system_read_map(images, sys, map, &err), &err, map);
    for (int i = 0; i < n2; i++)
        hl_alg_clear(&images[i], ctx);

    hl_scheme *s = NULL;
    fuzz_check_error(hl_scheme_from_map(&s, map, sys, &err), &err, map);
    hl_scheme_free(s);
    hl_system_free(sys);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *map = fuzz_string(data, size);
    read_map("(p^2 + x^2)/2", map);
    read_map("(px^2 + py^2)/2 + k*x^2*y", map);
    free(map);
    return 0;
}
