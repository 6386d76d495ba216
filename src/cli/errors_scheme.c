/* Which scheme `errors` analyses, as given: a catalog name (--scheme), a
 * map (--map) or equations (--equations).  Used by the symbolic and the
 * numeric analysis alike. */
#include "cli/errors.h"

const char *errors_source(const err_opts *r, const cli_opts *o)
{
    return r->scheme ? "catalog" : o->map ? "map" : "equations";
}

const char *errors_input(const err_opts *r, const cli_opts *o)
{
    return r->scheme ? r->scheme : o->map ? o->map : r->equations;
}

hl_status errors_make_scheme(hl_scheme **s, const err_opts *r, const cli_opts *o, hl_system *sys,
                             hl_error *err)
{
    int st;
    if (o->map != NULL) {
        if ((st = hl_scheme_from_map(s, o->map, sys, err)) != HL_OK)
            hl_error_prefix(err, "in --map");
    } else if (r->equations != NULL) {
        if ((st = hl_scheme_from_equations(s, r->equations, sys, err)) != HL_OK)
            hl_error_prefix(err, "in --equations");
    } else
        st = hl_scheme_new(s, r->scheme, 0, sys, err);
    return st;
}

