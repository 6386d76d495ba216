/* Fuzz target for `--pairs` ("x:px,y:py"), read by hl_system_new: any
 * input must give a system or be refused cleanly. */
#include "fuzz.h"
#include "hamlie/ham.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *pairs = fuzz_string(data, size);
    hl_system_spec spec = {"(px^2 + py^2)/2 + a*x^2*y + b*q*p", pairs, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_error err;
    fuzz_check_error(hl_system_new(&sys, &spec, &err), &err, pairs);
    hl_system_free(sys);
    free(pairs);
    return 0;
}
