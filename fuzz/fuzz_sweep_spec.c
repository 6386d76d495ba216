/* Fuzz target for a sweep's spec (sweep.h): the input's lines are the
 * points (a grid, or random bounds when it starts with '~', or an event
 * surface on a fixed grid when it starts with '!', or nothing: then the
 * CSV), the parameter values, the schemes and the steps; the rest
 * is a points CSV.  Only hl_sweep_new runs (no member).  A failure points
 * inside the field it names; an accepted sweep has members and columns. */
#include "fuzz.h"
#include "hamlie/sweep.h"

/* The next line of *s (cut in place), or "" at the end. */
static char *take_line(char **s)
{
    char *line = *s, *nl = strchr(line, '\n');
    if (nl == NULL) {
        *s = line + strlen(line);
        return line;
    }
    *nl = '\0';
    *s = nl + 1;
    return line;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *in = fuzz_string(data, size), *rest = in;
    char *points = take_line(&rest), *params = take_line(&rest), *schemes = take_line(&rest);
    char *dts = take_line(&rest);
    hl_sweep_spec spec = {.H = "p^2/2 - k*cos(q) + eps*q",
                          .params = params[0] ? params : "k=1,eps=0",
                          .schemes = schemes,
                          .dts = dts[0] ? dts : NULL,
                          .t = 1,
                          .nrandom = 3,
                          .seed = 5};
    if (points[0] == '~')
        spec.random = points + 1;
    else if (points[0] == '!') {
        spec.grid = "q=0:1:2,p=0.5";
        spec.event = points + 1;
        spec.save_every = 2;
    } else if (points[0] != '\0')
        spec.grid = points;
    else
        spec.points_csv = rest;
    hl_sweep *sw = NULL;
    hl_error err;
    hl_error_clear(&err);
    int st = hl_sweep_new(&sw, &spec, &err);
    const char *fields[] = {spec.grid, spec.random, spec.params,    spec.schemes,
                            spec.dts,  spec.event,  spec.points_csv};
    for (int i = 0; i < 7; i++)
        if (fields[i] != NULL)
            fuzz_check_error(st, &err, fields[i]);
    if (st != 0 && err.src != NULL) { /* a position is in one of the fields */
        int found = 0;
        for (int i = 0; i < 7; i++)
            found |= fields[i] != NULL && err.src == fields[i];
        if (!found)
            abort();
    }
    if (st == 0 && (sw == NULL || hl_sweep_count(sw) < 1 || hl_sweep_ncols(sw) < 10))
        abort();
    hl_sweep_free(sw);
    free(in);
    return 0;
}
