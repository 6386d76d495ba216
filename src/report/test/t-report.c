/* The report layer: JSON writer (nesting, commas, escapes, misuse), vector
 * fields and series in D written by hand for the oscillator and Kepler. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/ham.h"
#include "hamlie/report.h"
#include "hl_test.h"

static void test_json(void)
{
    hl_buf b;
    hl_json j;
    hl_buf_init(&b);
    hl_json_init_buf(&j, &b);
    j.pretty = 0;
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "a", "q\"\\\n\x01é");
    hl_json_key(&j, "list");
    hl_json_array_begin(&j);
    hl_json_int(&j, -3);
    hl_json_bool(&j, 1);
    hl_json_null(&j);
    hl_json_array_begin(&j);
    hl_json_array_end(&j);
    hl_json_object_begin(&j);
    hl_json_object_end(&j);
    hl_json_array_end(&j);
    hl_json_kv_bool(&j, "z", 0);
    hl_json_object_end(&j);
    CHECK(hl_json_finish(&j) == 0);
    CHECK_STR(b.s, "{\"a\":\"q\\\"\\\\\\n\\u0001é\",\"list\":[-3,true,null,[],{}],\"z\":false}\n");
    hl_buf_clear(&b);

    /* misuse is reported, not crashed on */
    hl_json_init_buf(&j, &b);
    hl_json_object_begin(&j);
    hl_json_key(&j, "k");
    hl_json_object_end(&j);
    CHECK(hl_json_finish(&j) != 0);
    hl_buf_clear(&b);
    hl_json_init_buf(&j, &b);
    hl_json_array_begin(&j);
    CHECK(hl_json_finish(&j) != 0);
    hl_buf_clear(&b);

    /* pretty output */
    hl_json_init_buf(&j, &b);
    hl_json_object_begin(&j);
    hl_json_kv_int(&j, "n", 1);
    hl_json_object_end(&j);
    CHECK(hl_json_finish(&j) == 0);
    CHECK_STR(b.s, "{\n  \"n\": 1\n}\n");
    hl_buf_clear(&b);
}

static hl_system *sys_of(const char *H)
{
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    if (hl_system_new(&sys, &spec, NULL) != HL_OK)
        exit(1);
    return sys;
}

static void test_fields(void)
{
    hl_system *sys = sys_of("(p^2+x^2)/2");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    hl_alg c[2];
    const char *names[2] = {"x", "p"};
    hl_alg_init(&c[0], ctx), hl_alg_init(&c[1], ctx);
    CHECK(hl_generator(&c[0], &c[1], sys, NULL) == HL_OK);
    char *s = hl_format_vector_field(2, names, c, ctx, pool, HL_STYLE_TEXT);
    CHECK_STR(s, "p ∂/∂x − x ∂/∂p");
    free(s);
    s = hl_format_vector_field(2, names, c, ctx, pool, HL_STYLE_LATEX);
    CHECK_STR(s, "p \\frac{\\partial}{\\partial x} - x \\frac{\\partial}{\\partial p}");
    free(s);
    /* a coefficient -1 and a sum: −∂/∂x + (x + 1) ∂/∂p; zero components left out */
    CHECK(hl_system_read(&c[0], sys, "-1", NULL) == HL_OK);
    CHECK(hl_system_read(&c[1], sys, "x + 1", NULL) == HL_OK);
    s = hl_format_vector_field(2, names, c, ctx, pool, HL_STYLE_TEXT);
    CHECK_STR(s, "−∂/∂x + (x + 1) ∂/∂p");
    free(s);
    hl_alg_zero(&c[0], ctx);
    hl_alg_zero(&c[1], ctx);
    s = hl_format_vector_field(2, names, c, ctx, pool, HL_STYLE_TEXT);
    CHECK_STR(s, "0");
    free(s);

    /* the oscillator series of x: x + D p - D^2/2 x - D^3/6 p + D^4/24 x */
    hl_alg t[5];
    for (int k = 0; k < 5; k++)
        hl_alg_init(&t[k], ctx);
    CHECK(hl_system_read(&t[0], sys, "x", NULL) == HL_OK);
    CHECK(hl_lie_terms(t, &t[0], 4, sys, NULL) == HL_OK);
    s = hl_format_series(t, 4, "D", 1, ctx, pool, HL_STYLE_TEXT);
    CHECK_STR(s, "x + D*p - D^2/2*x - D^3/6*p + D^4/24*x");
    free(s);
    s = hl_format_series(t, 4, "D", 1, ctx, pool, HL_STYLE_SYMPY);
    CHECK_STR(s, "x + D*p - D**2/2*x - D**3/6*p + D**4/24*x");
    free(s);
    s = hl_format_series(t, 2, "D", 0, ctx, pool, HL_STYLE_TEXT); /* no factorials */
    CHECK_STR(s, "x + D*p - D^2*x");
    free(s);
    /* coefficients with a denominator: one fraction, no "D*1/x^2" */
    CHECK(hl_system_read(&t[0], sys, "p", NULL) == HL_OK);
    CHECK(hl_system_read(&t[1], sys, "-1/x^2", NULL) == HL_OK);
    CHECK(hl_system_read(&t[2], sys, "1/x^2", NULL) == HL_OK);
    CHECK(hl_system_read(&t[3], sys, "2*p/x^3", NULL) == HL_OK);
    s = hl_format_series(t, 3, "D", 1, ctx, pool, HL_STYLE_TEXT);
    CHECK_STR(s, "p - D/x^2 + D^2/(2*x^2) + D^3*p/(3*x^3)");
    free(s);
    s = hl_format_series(t, 2, "D", 1, ctx, pool, HL_STYLE_LATEX);
    CHECK_STR(s, "p - \\frac{D}{x^{2}} + \\frac{D^{2}}{2\\,x^{2}}");
    free(s);
    for (int k = 0; k < 5; k++)
        hl_alg_zero(&t[k], ctx);
    s = hl_format_series(t, 4, "D", 1, ctx, pool, HL_STYLE_TEXT);
    CHECK_STR(s, "0");
    free(s);
    for (int k = 0; k < 5; k++)
        hl_alg_clear(&t[k], ctx);
    hl_alg_clear(&c[0], ctx), hl_alg_clear(&c[1], ctx);
    hl_system_free(sys);
}

int main(void)
{
    test_json();
    test_fields();
    return HL_TEST_END();
}
