/* Fuzz target for the surfaces of section: the input's first line is a
 * surface (`--surface x=0`, `--event 'x^2 + y = 1'`), read by
 * hl_run_surface and hl_section_new; the rest is a points file
 * (`--init-file`), read by hl_section_read_points on Henon-Heiles at
 * E = 1/8.  Failures point inside the text they read; accepted points are
 * finite and on the energy surface. */
#include <math.h>

#include "fuzz.h"
#include "hamlie/ham.h"
#include "hamlie/run.h"
#include "hamlie/section.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *in = fuzz_string(data, size);
    char *nl = strchr(in, '\n');
    const char *points = "";
    if (nl != NULL) {
        *nl = '\0';
        points = nl + 1;
    }
    hl_system_spec spec = {"(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3", NULL, NULL, NULL,
                           NULL};
    hl_system *sys;
    hl_error err;
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        abort();
    hl_run_surface_info info;
    fuzz_check_error(hl_run_surface(&info, sys, in, &err), &err, in);
    hl_section *sec = NULL;
    int st = hl_section_new(&sec, sys, in, HL_EVENT_UP, 0.125, &err);
    fuzz_check_error(st, &err, in);
    if (st == HL_OK) {
        double *zs = NULL;
        int n = 0;
        st = hl_section_read_points(sec, points, &zs, &n, &err);
        fuzz_check_error(st, &err, points);
        for (int i = 0; st == HL_OK && i < 4 * n; i++)
            if (!isfinite(zs[i]))
                abort();
        free(zs);
    }
    hl_section_free(sec);
    hl_system_free(sys);
    free(in);
    return 0;
}
