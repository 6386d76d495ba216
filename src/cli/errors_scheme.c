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
    return cli_make_scheme(s, o->map, r->equations, r->scheme, 0, sys, err);
}

