/* Internals shared by the files of src/series only. */
#ifndef HAMLIE_SERIES_IMPL_H
#define HAMLIE_SERIES_IMPL_H

#include "hamlie/series.h"
#include "rules/rule.h"

/* Structurally zero?  For skipping work only: hl_alg_is_zero may run a
 * numeric test (and flag the context) where the canonical form does not
 * decide, which a skipped product does not need. */
static inline int series_trivially_zero(const hl_alg *a, const hl_alg_ctx *ctx)
{
    return fmpz_mpoly_is_zero(a->num, hl_alg_ctx_mpoly(ctx));
}

/* A table of symbol values for hl_series_eval_expr: every base symbol of the
 * context bound to itself (a constant series), the step var_D (if >= 0) to
 * the series D; names are borrowed. */
typedef struct series_table {
    int nsym, alloc;
    const char **names;
    hl_series *vals;
} series_table;

void series_table_init(series_table *t, int var_D, int n, hl_alg_ctx *ctx);
void series_table_clear(series_table *t, const hl_alg_ctx *ctx);
/* Bind name to v (a copy), replacing an earlier binding of the same name;
 * returns its index in names/vals. */
int series_table_bind(series_table *t, const char *name, const hl_series *v, const hl_alg_ctx *ctx);
int series_table_eval(hl_series *out, const hl_expr *e, const series_table *t, int n,
                      hl_alg_ctx *ctx, hl_error *err);

/* Taylor mode compiled (taylor.c): the nodes of the expressions roots, in
 * topological order, symbols resolved to indices into names.  A program is
 * run coefficient by coefficient: step k computes the D^k coefficient of
 * every node from inputs[i].c[k] and the coefficients below k; running step
 * k again (after changing inputs' coefficient k) overwrites it, and step 0
 * restarts the run. */
typedef struct series_prog series_prog;

int series_prog_compile(series_prog **out, int nroot, const hl_expr *const *roots, int nsym,
                        const char *const *names, int n, hl_alg_ctx *ctx, hl_error *err);
void series_prog_free(series_prog *p, const hl_alg_ctx *ctx); /* NULL is a no-op */
int series_prog_step(series_prog *p, int k, const hl_series *inputs, hl_alg_ctx *ctx,
                     hl_error *err);
int series_prog_run(series_prog *p, int n, const hl_series *inputs, hl_alg_ctx *ctx,
                    hl_error *err); /* steps 0..n-1 */
const hl_series *series_prog_root(const series_prog *p, int i);
/* Steps refuse (HL_ELIMIT) once the nodes' coefficients, all together,
 * pass max_terms terms (numerators and denominators; 0: no limit, the
 * default). */
void series_prog_set_budget(series_prog *p, long max_terms);

/* The exact back end of the rules (emit.c): runs an operation's rule on
 * hl_alg coefficients.  Before a run the caller points slot[] at the
 * series of the operands and results, keep at the node's two kept values,
 * and sets exponent (B's coefficient 0 of a^c, else NULL) and vanishing
 * (the message when a divisor is zero at D = 0). */
typedef struct series_val series_val;
typedef struct series_em {
    hl_em em;
    hl_series *slot[HL_SLOT_COUNT];
    hl_alg *keep;
    const fmpq *exponent;
    const char *vanishing;
    hl_alg_ctx *ctx;
    hl_error *err;
    int status;
    series_val **val; /* temporaries, reused from run to run */
    int nval, aval;
} series_em;

void series_em_init(series_em *E, hl_alg_ctx *ctx);
void series_em_clear(series_em *E);
/* Coefficient k by the rule; the first error of the run (HL_OK if none). */
int series_em_run(series_em *E, const hl_rule *rule, int k, hl_error *err);

#endif
