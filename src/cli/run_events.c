/* hamlie run --event: the crossings of a surface, recorded with the run
 * (cmd_run.c runs; this file reads the options, keeps the crossings and
 * writes them through crossings.c). */
#include <stdlib.h>
#include <string.h>

#include "cli/crossings.h"
#include "cli/run.h"

void run_events_found(run_opts *r, int k, const char *value)
{
    const char **slot[] = {&r->event, &r->direction, &r->event_stop_s, &r->events_out};
    *slot[k] = value;
}

int run_events_check(run_opts *r, const cli_opts *o, const cli_command *cmd)
{
    if (r->event == NULL) {
        if (r->direction || r->event_stop_s || r->events_out)
            return cli_usage(cmd, "--direction, --event-stop and --events-out are for --event");
        return -1;
    }
    r->dir = HL_EVENT_BOTH;
    if (r->direction != NULL && crossings_direction(&r->dir, r->direction) != 0)
        return cli_usage(cmd, "--direction wants up, down or both, not '%s'", r->direction);
    if (r->event_stop_s != NULL) {
        char *end;
        r->event_stop = strtol(r->event_stop_s, &end, 10);
        if (*r->event_stop_s == '\0' || *end != '\0' || r->event_stop < 1)
            return cli_usage(cmd, "--event-stop wants a whole number >= 1, not '%s'",
                             r->event_stop_s);
    }
    if (r->digits_s != NULL)
        return cli_usage(cmd, "--event is not located by the Arb integrator (--digits) yet: use "
                              "--tol (crossings to round-off on the Taylor polynomial)");
    if (r->orders != NULL)
        return cli_usage(cmd, "--event records the crossings of one run: not with --orders");
    const char *path = r->events_out;
    if (path == NULL && r->out != NULL) { /* next to the trajectory */
        size_t n = strlen(r->out) + 12;
        r->events_path = hl_xmalloc(n);
        snprintf(r->events_path, n, "%s.events.csv", r->out);
    } else if (path != NULL) {
        if (strcmp(path, "-") == 0 && r->out == NULL && o->format != CLI_JSON)
            return cli_usage(cmd, "--events-out -: standard output has the trajectory; give "
                                  "--out FILE for it");
        r->events_path = hl_xstrdup(path);
    } else if (o->format != CLI_JSON)
        return cli_usage(cmd, "--event: where do the crossings go? --events-out FILE (or "
                              "--out FILE: then FILE.events.csv; or --json)");
    r->cross = hl_xcalloc(1, sizeof *r->cross);
    return -1;
}

static int keep(const hl_run_crossing *c, void *arg)
{
    crossings_add(arg, 0, c);
    return 0;
}

int run_events_setup(hl_run *run, const run_opts *r, hl_system *sys, hl_error *err)
{
    if (r->event == NULL)
        return HL_OK;
    crossings_init(r->cross, 2 * hl_system_ndof(sys));
    int st = hl_run_event(run, r->event, r->dir, r->event_stop, keep, r->cross, err);
    if (st != HL_OK)
        hl_error_prefix(err, "in --event");
    return st;
}

/* How the crossings were located, in words. */
static const char *located(const hl_run *run)
{
    return hl_run_event_order(run) == 0
               ? "on the Taylor integrator's step polynomials, to round-off"
               : "on the cubic Hermite interpolant of each step (local order 4), on top of the "
                 "scheme's error";
}

int run_events_write(const run_opts *r, hl_system *sys)
{
    if (r->event == NULL || r->events_path == NULL)
        return CLI_OK;
    return crossings_write_csv(r->cross, sys, r->events_path, 0);
}

void run_events_say(hl_buf *out, const run_opts *r, const hl_run_stats *s, const hl_run *run)
{
    if (r->event == NULL || r->events_path == NULL)
        return;
    hl_buf_printf(out, "%ld crossings of %s (%s)%s, located %s; wrote them to %s\n", r->cross->n,
                  r->event, crossings_direction_name(r->dir),
                  s->event_stop ? ", the run stopped at the last" : "", located(run),
                  r->events_path);
}

void run_events_json(hl_json *j, const run_opts *r, hl_system *sys, const hl_run *run,
                     const hl_run_stats *s)
{
    if (r->event == NULL)
        return;
    hl_json_key(j, "event");
    hl_json_object_begin(j);
    hl_json_kv_string(j, "surface", r->event);
    hl_json_kv_string(j, "direction", crossings_direction_name(r->dir));
    hl_json_kv_string(j, "located_on",
                      hl_run_event_order(run) == 0 ? "taylor-polynomial" : "hermite-cubic");
    hl_json_kv_int(j, "interpolant_local_order", hl_run_event_order(run));
    hl_json_kv_int(j, "crossings", r->cross->n);
    hl_json_kv_bool(j, "stopped", s->event_stop);
    hl_json_kv_string(j, "out", r->events_path);
    if (r->events_path == NULL)
        crossings_json(r->cross, j, "table", sys, 0);
    hl_json_object_end(j);
}

void run_events_free(run_opts *r)
{
    if (r->cross != NULL)
        crossings_clear(r->cross);
    free(r->cross);
    free(r->events_path);
}
