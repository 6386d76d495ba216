/* Fuzz target for initial points (`--init x=1,p=pi/2`): hl_run_init_values
 * in double and hl_run_init_values_arb, on a system with two degrees of
 * freedom and a set parameter.  A point that is accepted is finite. */
#include <math.h>

#include <arb.h>

#include "fuzz.h"
#include "hamlie/ham.h"
#include "hamlie/run.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *init = fuzz_string(data, size);
    hl_system_spec spec = {"(px^2 + py^2)/2 + k*x^2*y", NULL, "k=1/3", NULL, NULL};
    hl_system *sys;
    hl_error err;
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        abort();

    double z[4];
    int st = hl_run_init_values(z, sys, init, &err);
    fuzz_check_error(st, &err, init);
    for (int i = 0; st == HL_OK && i < 4; i++)
        if (!isfinite(z[i]))
            abort();

    arb_ptr za = _arb_vec_init(4);
    fuzz_check_error(hl_run_init_values_arb(za, sys, init, 128, &err), &err, init);
    _arb_vec_clear(za, 4);

    hl_system_free(sys);
    free(init);
    return 0;
}
