/* Systems from text: default pairing, --pairs, --param, and the errors a
 * user meets, each with its position in the text. */
#include <string.h>

#include "ham_test.h"

typedef struct pairing_case {
    const char *H, *pairs, *params;
    const char *want; /* "q:p,..;params" */
} pairing_case;

static void describe(char *out, size_t n, hl_system *sys)
{
    out[0] = '\0';
    for (int j = 0; j < hl_system_ndof(sys); j++)
        snprintf(out + strlen(out), n - strlen(out), "%s%s:%s", j ? "," : "",
                 hl_system_coord(sys, j), hl_system_momentum(sys, j));
    snprintf(out + strlen(out), n - strlen(out), ";");
    for (int i = 0; i < hl_system_nparams(sys); i++)
        snprintf(out + strlen(out), n - strlen(out), "%s%s", i ? "," : "", hl_system_param(sys, i));
}

static const pairing_case good[] = {
    {"(p^2+x^2)/2", NULL, NULL, "x:p;"},
    {"p^2/2 - cos(q)", NULL, NULL, "q:p;"},
    {"q^2", NULL, NULL, "q:p;"},
    {"(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", NULL, NULL, "x:px,y:py;"},
    {"py^2/2 + k*x^2 + px", NULL, NULL, "x:px,y:py;k"},
    {"pz + z*py + y*x*px", NULL, NULL, "x:px,y:py,z:pz;"},
    {"pb^2 + b*a*pa", NULL, NULL, "a:pa,b:pb;"},
    {"py*y + pb*b*px*x", NULL, NULL, "x:px,y:py,b:pb;"},
    {"py^2/2 + k*x^2 + px", "y:py,x:px", NULL, "y:py,x:px;k"},
    {"k10*q + k9*p + k*q + omega*k2", NULL, NULL, "q:p;k2,k9,k10,k,omega"},
    {"(p1^2+p2^2+p10^2)/2 + q2*q1", NULL, NULL, "q1:p1,q2:p2,q10:p10;"},
    {"p^2/(2*m) + k*q^2/2", NULL, NULL, "q:p;k,m"},
    {"p^2/(2*m) + k*q^2/2", NULL, "k=2, m=1/2", "q:p;"},
    {"p^2/(2*m) + k*q^2/2", NULL, "m=3", "q:p;k"},
    {"u^2 + v^2 + a*u", "u:v", NULL, "u:v;a"},
    {"a*b", " a : b ", NULL, "a:b;"},
    {"p^2/2", "q:p", NULL, "q:p;"},
};

typedef struct bad_case {
    const char *H, *pairs, *params;
    hl_status status;
    const char *where; /* "H", "pairs", "params" */
    int pos;
    const char *msg;   /* a piece of the message */
} bad_case;

static const bad_case bad[] = {
    {"p^2/2", NULL, NULL, HL_EINVAL, "H", 0, "--pairs"},
    {"x^2 + y^2", NULL, NULL, HL_EINVAL, NULL, -1, "--pairs"},
    {"p^2/2", "x:", NULL, HL_EINVAL, "pairs", 2, "momentum missing"},
    {"p^2/2", "x", NULL, HL_EPARSE, "pairs", 1, "':'"},
    {"p^2/2", "x:p,x:px", NULL, HL_EINVAL, "pairs", 4, "used twice"},
    {"p^2/2", "x:x", NULL, HL_EINVAL, "pairs", 0, "used twice"},
    {"p^2/2", "D:p", NULL, HL_EINVAL, "pairs", 0, "step"},
    {"p^2/2", "x:p;", NULL, HL_EPARSE, "pairs", 3, "','"},
    {"p^2/2+k*q", NULL, "k=x", HL_EINVAL, "params", 2, "not a constant"},
    {"p^2/2+k*q", NULL, "j=2", HL_EINVAL, "params", 0, "no symbol 'j'"},
    {"p^2/2+k*q", NULL, "q=2", HL_EINVAL, "params", 0, "phase variable"},
    {"p^2/2+k*q", NULL, "k=1,k=2", HL_EINVAL, "params", 4, "twice"},
    {"p^2/2+k*q", NULL, "k=1/0", HL_EDOM, "params", -2, "division by zero"},
    {"p^2/2+k*q", NULL, "k=(2", HL_EPARSE, "params", -2, "')'"},
    {"p^2/2+k*q", NULL, "k", HL_EPARSE, "params", 1, "'='"},
    {"(p^2+q^2/2", NULL, NULL, HL_EPARSE, "H", -2, "')'"},
    {"p^2 + foo(q)", NULL, NULL, HL_EPARSE, "H", 6, "foo"},
    {"p^2 + H", NULL, NULL, HL_EINVAL, "H", 6, "'H'"},
};

static void test_good(void)
{
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        hl_system_spec spec = {good[i].H, good[i].pairs, good[i].params, NULL, NULL};
        hl_system *sys = NULL;
        hl_error err;
        hl_error_clear(&err);
        int st = hl_system_new(&sys, &spec, &err);
        CHECK_MSG(st == HL_OK, "%s: %s", good[i].H, err.msg);
        if (st != HL_OK)
            continue;
        char got[256];
        describe(got, sizeof got, sys);
        CHECK_STR(got, good[i].want);
        CHECK(hl_system_var_D(sys) == 2 * hl_system_ndof(sys) + hl_system_nparams(sys));
        CHECK_STR(hl_alg_ctx_name(hl_system_ctx(sys), hl_system_var_D(sys)), "D");
        hl_system_free(sys);
    }
}

static void test_bad(void)
{
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const bad_case *c = &bad[i];
        hl_system_spec spec = {c->H, c->pairs, c->params, NULL, NULL};
        hl_system *sys = NULL;
        hl_error err;
        hl_error_clear(&err);
        int st = hl_system_new(&sys, &spec, &err);
        CHECK_MSG(st == (int)c->status, "case %zu: status %d, want %d (%s)", i, st, c->status,
                  err.msg);
        CHECK(sys == NULL);
        CHECK_MSG(strstr(err.msg, c->msg) != NULL, "case %zu: message '%s' lacks '%s'", i,
                  err.msg, c->msg);
        const char *src = c->where == NULL ? NULL
                          : strcmp(c->where, "H") == 0 ? c->H
                          : strcmp(c->where, "pairs") == 0 ? c->pairs : c->params;
        CHECK_MSG(err.src == src, "case %zu: error in the wrong text", i);
        if (c->pos >= -1)
            CHECK_MSG(err.pos == c->pos, "case %zu: pos %d, want %d", i, err.pos, c->pos);
        else
            CHECK_MSG(err.pos >= 0, "case %zu: no position", i);
    }
}

static void test_read(void)
{
    hl_system *sys = sys_new("(px^2+py^2)/2 - k/sqrt(x^2+y^2)", NULL);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg a;
    hl_error err;
    hl_alg_init(&a, ctx);
    hl_error_clear(&err);
    const char *f = "x*py - z*px";
    CHECK(hl_system_read(&a, sys, f, &err) == HL_EINVAL);
    CHECK(err.src == f && err.pos == 7);
    CHECK_STR(err.msg, "unknown symbol 'z': not a coordinate, momentum or parameter of this "
                       "system (coordinates x, y; momenta px, py; parameter k)");
    CHECK(hl_system_read(&a, sys, "H - k*D", &err) == HL_OK);
    CHECK(eq_formula(&a, sys, "(px^2+py^2)/2 - k/sqrt(x^2+y^2) - k*D"));
    CHECK(hl_system_read(&a, sys, "x/(y-y)", &err) == HL_EDOM);
    CHECK(hl_system_read(&a, sys, "x +* y", &err) == HL_EPARSE);
    CHECK(err.pos == 3);

    /* maps: names, wrong names, counts, positions */
    hl_alg img[4];
    for (int i = 0; i < 4; i++)
        hl_alg_init(&img[i], ctx);
    CHECK(hl_system_read_map(img, sys, "PY = py; X = x + D*px; Y = y; PX = px", &err) == HL_OK);
    CHECK(eq_formula(&img[0], sys, "x + D*px"));
    CHECK(eq_formula(&img[3], sys, "py"));
    const char *m = "X = x; Y = y; PX = px; PY = w";
    CHECK(hl_system_read_map(img, sys, m, &err) == HL_EINVAL);
    CHECK(err.src == m && err.pos == 28);
    /* an image may use the images before it (symplectic Euler's stages) */
    m = "PX = px - D*x; PY = py - D*k*y; X = x + D*PX; y' = y + D*py'";
    CHECK(hl_system_read_map(img, sys, m, &err) == HL_OK);
    CHECK(eq_formula(&img[0], sys, "x + D*(px - D*x)"));
    CHECK(eq_formula(&img[1], sys, "y + D*(py - D*k*y)"));
    CHECK(eq_formula(&img[2], sys, "px - D*x"));
    m = "X = x + D*px'; Y = y; PX = px; PY = py"; /* px' before its image */
    CHECK(hl_system_read_map(img, sys, m, &err) == HL_EINVAL);
    CHECK_MSG(err.src == m && err.pos == 10, "pos %d", err.pos);
    CHECK(strstr(err.msg, "before its image") != NULL);
    CHECK(hl_system_read_map(img, sys, "X = x; Y = y; PX = px", &err) == HL_EINVAL);
    CHECK(hl_system_read_map(img, sys, "X = x; X = y; PX = px; PY = py", &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "twice") != NULL);
    CHECK(hl_system_read_map(img, sys, "X = x; Z = y; PX = px; PY = py", &err) == HL_EINVAL);
    CHECK(err.pos == 7);
    for (int i = 0; i < 4; i++)
        hl_alg_clear(&img[i], ctx);
    hl_alg_clear(&a, ctx);
    hl_system_free(sys);

    /* H in a map-only system */
    const char *extra[] = {"X = x + D*p; P = p", NULL};
    hl_system_spec spec = {NULL, NULL, NULL, extra, NULL};
    CHECK(hl_system_new(&sys, &spec, &err) == HL_OK);
    CHECK(!hl_system_has_H(sys) && hl_system_H(sys) == NULL);
    hl_alg_init(&a, hl_system_ctx(sys));
    CHECK(hl_system_read(&a, sys, "x + H", &err) == HL_EINVAL && err.pos == 4);
    CHECK(hl_generator_apply(&a, &a, sys, &err) == HL_EINVAL);
    hl_alg_clear(&a, hl_system_ctx(sys));
    hl_system_free(sys);
}

/* The step's name: refused in H and in phase functions; renamed, the old
 * name is an ordinary parameter and the new one is the step everywhere. */
static void test_step(void)
{
    hl_system *sys = NULL;
    hl_error err;
    hl_system_spec morse = {"p^2/2 + D*(1-exp(-q))^2", NULL, NULL, NULL, NULL};
    CHECK(hl_system_new(&sys, &morse, &err) == HL_EINVAL && sys == NULL);
    CHECK(err.pos == 8 && err.src == morse.H && strstr(err.msg, "step") != NULL);

    morse.step = "h";
    CHECK(hl_system_new(&sys, &morse, &err) == HL_OK);
    CHECK(strcmp(hl_system_step(sys), "h") == 0);
    CHECK(hl_system_nparams(sys) == 1 && strcmp(hl_system_param(sys, 0), "D") == 0);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    CHECK(strcmp(hl_alg_ctx_name(ctx, hl_system_var_D(sys)), "h") == 0);
    hl_alg a;
    hl_alg_init(&a, ctx);
    CHECK(hl_system_read(&a, sys, "q + h*p + D", &err) == HL_OK);
    CHECK(hl_alg_depends_on(&a, hl_system_var_D(sys), ctx));
    CHECK(hl_system_read_phase(&a, sys, "q + D", &err) == HL_OK);
    CHECK(hl_system_read_phase(&a, sys, "q + h", &err) == HL_EINVAL && err.pos == 4);
    hl_alg_clear(&a, ctx);
    hl_system_free(sys);

    static const char *const bad_steps[] = {"sin", "H", "pi", "", "2h", "h h"};
    for (size_t i = 0; i < sizeof bad_steps / sizeof *bad_steps; i++) {
        hl_system_spec spec = {"p^2/2 - cos(q)", NULL, NULL, NULL, bad_steps[i]};
        CHECK_MSG(hl_system_new(&sys, &spec, &err) == HL_EINVAL, "step '%s'", bad_steps[i]);
    }
    hl_system_spec pairs = {"ph^2/2", "h:ph", NULL, NULL, "h"};
    CHECK(hl_system_new(&sys, &pairs, &err) == HL_EINVAL && err.pos == 0);
    hl_system_spec param = {"p^2/2 + k*q", NULL, "D=1", NULL, NULL};
    CHECK(hl_system_new(&sys, &param, &err) == HL_EINVAL && strstr(err.msg, "step") != NULL);
}

int main(void)
{
    test_good();
    test_bad();
    test_read();
    test_step();
    hl_system_free(NULL);
    return HL_TEST_END();
}
