/* The crossings of a surface (events) as the CLI keeps and writes them: a
 * table of rows (orbit, crossing, t, the state, H), written as CSV or into
 * a JSON array.  Kept apart from the commands (run --event, section) so
 * that another format (HDF5, with the sweeps) is one more writer here. */
#ifndef HAMLIE_CLI_CROSSINGS_H
#define HAMLIE_CLI_CROSSINGS_H

#include "cli/cli.h"
#include "hamlie/run.h"

typedef struct crossings {
    int n2;       /* the state's size */
    long n, cap;  /* rows kept, room */
    double *rows; /* n rows of 3 + n2 + 1: orbit, crossing, t, z, H */
    long nfailed; /* orbits that failed (crossings_orbit_failed): */
    struct crossings_failure {
        long orbit;
        int status;   /* an hl_status */
        char *reason; /* malloc'd */
    } * failures;
} crossings;

void crossings_init(crossings *c, int n2);
void crossings_clear(crossings *c);
void crossings_add(crossings *c, long orbit, const hl_run_crossing *x);
const double *crossings_row(const crossings *c, long i);

/* The CSV: a header "orbit,crossing,t,x,y,px,py,H" (without orbit unless
 * with_orbit), then one line a row, numbers with 17 digits.  Written to
 * PATH.tmp and renamed to PATH ("-": standard output).  CLI_OK, or
 * CLI_ERROR after the message (nothing left under PATH). */
int crossings_write_csv(const crossings *c, hl_system *sys, const char *path, int with_orbit);

/* An orbit that failed (its crossings found before stay): its reason is
 * its status in the HDF5 file. */
void crossings_orbit_failed(crossings *c, long orbit, const hl_error *err);

/* What an HDF5 file of crossings records besides them (crossings_write_h5):
 * the inputs, and the orbits' starts (norbits x n2, seeds[i*n2 ..]). */
typedef struct crossings_h5_info {
    const char *command, *H, *energy_input, *surface, *direction, *scheme, *located_on;
    double energy, tol, dt, t_max; /* tol or dt: the one > 0 is written */
    long norbits, per_orbit;
    const double *seeds;
} crossings_h5_info;

/* The HDF5 file (layout in docs/commands/section.md): group "crossings",
 * one dataset a column (orbit, crossing, t, the state, H); group
 * "orbits" (the start, crossings found, status, reason of each); the
 * inputs as the root's attributes.  Written through a temporary (h5.h):
 * CLI_OK, or CLI_ERROR after the message with nothing left under path. */
int crossings_write_h5(const crossings *c, hl_system *sys, const char *path,
                       const crossings_h5_info *info);

/* "key": [{"orbit":..,"crossing":..,"t":..,"state":{..},"H":..}, ...] */
void crossings_json(const crossings *c, hl_json *j, const char *key, hl_system *sys,
                    int with_orbit);

/* "up", "down", "both" -> the direction; -1 when it is none of them. */
int crossings_direction(hl_event_dir *dir, const char *s);
const char *crossings_direction_name(hl_event_dir dir);

#endif
