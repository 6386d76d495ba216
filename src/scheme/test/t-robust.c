/* The readers never crash or leak on bad text: malformed definitions, and
 * random one-byte mutations, deletions and truncations of valid ones, are
 * each either rejected with a message or accepted and then expanded (to a
 * few coefficients) and compiled for stepping — success or a clean error,
 * never an abort (the sanitizer build checks memory).  Deterministic: a
 * fixed LCG seed. */
#include "sch.h"

static unsigned long rng = 12345;
static unsigned next_rand(void)
{
    rng = rng * 6364136223846793005UL + 1442695040888963407UL;
    return (unsigned)(rng >> 33);
}

static int accepted, rejected;

static void try_text(hl_system *sys, const char *t, int kind)
{
    hl_scheme *s = NULL;
    hl_error err;
    hl_error_clear(&err);
    int rc = kind == 0   ? hl_scheme_from_text(&s, t, sys, &err)
             : kind == 1 ? hl_scheme_from_map(&s, t, sys, &err)
                         : hl_scheme_from_equations(&s, t, sys, &err);
    if (rc != HL_OK) {
        rejected++;
        CHECK_MSG(s == NULL && err.msg[0] != '\0', "'%s': rejected without a message", t);
        CHECK_MSG(err.pos < 0 || (err.src != NULL && err.pos <= (int)strlen(err.src)),
                  "'%s': position %d outside the text", t, err.pos);
        return;
    }
    accepted++;
    hl_series *Z = new_series(2 * s->N, hl_system_ctx(sys));
    rc = hl_scheme_expand(Z, s, 3, &err);
    CHECK_MSG(rc == HL_OK || err.msg[0] != '\0', "'%s': expand failed silently", t);
    free_series(Z, 2 * s->N, hl_system_ctx(sys));
    hl_scheme_stepper *st = NULL;
    if (hl_scheme_stepper_new(&st, s, &err) == HL_OK) {
        double z[4] = {0.3, -0.2, 0.1, 0.25};
        rc = hl_scheme_step(st, z, 0.01, 0, &err);
        CHECK_MSG(rc == HL_OK || err.msg[0] != '\0', "'%s': step failed silently", t);
    }
    hl_scheme_stepper_free(st);
    hl_scheme_free(s);
}

static void mutate_all(hl_system *sys, const char *src, int kind, int rounds)
{
    static const char alphabet[] = "qpQPDHk1s(),;=+-*/^ .e0int";
    size_t n = strlen(src);
    char *buf = malloc(n + 2);
    for (int r = 0; r < rounds; r++) {
        memcpy(buf, src, n + 1);
        size_t at = next_rand() % n;
        switch (next_rand() % 3) {
        case 0: buf[at] = alphabet[next_rand() % (sizeof alphabet - 1)]; break;
        case 1: memmove(buf + at, buf + at + 1, n - at); break;
        default: buf[at] = '\0'; break;
        }
        try_text(sys, buf, kind);
    }
    free(buf);
}

int main(void)
{
    hl_system *pend = make_system("p^2/2 - cos(q)");
    hl_system *osc = make_system("(p^2 + x^2)/2");
    const char *fixed[] = {"", ";", "=", "Q", "Q =", "= q", "Q = q;;", "Q = q, P = p",
                           "Q = (q; P = p", "Q = q)", "Q = Hq(q)", "Q = Hq(q, p, p)",
                           "Q = int(1, q)", "Q = int(s q)", "Q = int(s, s; P = p",
                           "Q = q + D*p; P = p - D*sin(q); P = p", "Q = 1e99999999; P = p",
                           "Q = q/0; P = p", "Q = q^q^q^q; P = p", "Q = dot(q); P = p",
                           "D = q; Q = q; P = p", "pi = 3; Q = q; P = p", "q = Q; P = p",
                           "Q = Q; P = P", "k = Q; Q = k; P = p"};
    for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++) {
        try_text(pend, fixed[i], 0);
        try_text(osc, fixed[i], 1);
        try_text(osc, fixed[i], 2);
    }
    for (int i = 0; i < hl_scheme_catalog_count(); i++) {
        const char *t = hl_scheme_text(hl_scheme_catalog(i)->name);
        if (t)
            mutate_all(pend, t, 0, 40);
    }
    mutate_all(osc, "X = x + D*p; P = p - D*X", 1, 100);
    mutate_all(osc, "(X-x)/D = (P^2-p^2)/(2*(P-p)); (P-p)/D = -(X^2-x^2)/(2*(X-x))", 2, 100);
    printf("%d accepted, %d rejected\n", accepted, rejected);
    CHECK(accepted > 20 && rejected > 100);
    hl_system_free(pend);
    hl_system_free(osc);
    return HL_TEST_END();
}
