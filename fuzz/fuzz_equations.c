/* Fuzz target for the scheme language: `--equations` (hl_scheme_from_equations,
 * "(X-x)/D = (P+p)/2; ...") and `--scheme` definitions (hl_scheme_from_text,
 * src/scheme/read.c).  Any input must build a scheme or be refused cleanly. */
#include "fuzz.h"
#include "hamlie/ham.h"
#include "hamlie/scheme.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = fuzz_string(data, size);
    hl_system_spec spec = {"p^2/2 - cos(q)", NULL, NULL, NULL, NULL};
    hl_system *sys;
    hl_error err;
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        abort();

    hl_scheme *s = NULL;
    fuzz_check_error(hl_scheme_from_equations(&s, text, sys, &err), &err, text);
    hl_scheme_free(s);
    s = NULL;
    fuzz_check_error(hl_scheme_from_text(&s, text, sys, &err), &err, text);
    hl_scheme_free(s);

    hl_system_free(sys);
    free(text);
    return 0;
}
