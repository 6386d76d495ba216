/* Fuzz target for `--param` ("k=2,omega=1/3"), read by hl_system_new: any
 * input must give a system or be refused cleanly. */
#include "fuzz.h"
#include "hamlie/ham.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *params = fuzz_string(data, size);
    hl_system_spec spec = {"(p^2 + omega^2*x^2)/2 + k*x^4", NULL, params, NULL, NULL};
    hl_system *sys = NULL;
    hl_error err;
    fuzz_check_error(hl_system_new(&sys, &spec, &err), &err, params);
    hl_system_free(sys);
    free(params);
    return 0;
}
