/* Test helper: build an expected DAG from prefix notation, independently of
 * the parser under test: "(neg (pow x 2))", "(div (num -1/2) y)", "pi".
 * Atoms: integers and fractions (with optional '-') are numbers, "pi" is pi,
 * anything else a symbol.  Heads: neg add sub mul div pow and the function
 * names. */
#ifndef HL_TEST_SX_H
#define HL_TEST_SX_H

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "hamlie/expr.h"

static inline const hl_expr *sx_read(hl_pool *pool, const char **s)
{
    while (**s == ' ')
        (*s)++;
    if (**s == '(') {
        char head[16];
        int n = 0;
        (*s)++;
        while (**s != ' ' && **s != ')' && n < 15)
            head[n++] = *(*s)++;
        head[n] = '\0';
        const hl_expr *a = sx_read(pool, s), *b = NULL;
        while (**s == ' ')
            (*s)++;
        if (**s != ')')
            b = sx_read(pool, s);
        while (**s == ' ')
            (*s)++;
        (*s)++; /* ')' */
        if (!strcmp(head, "neg")) return hl_neg(pool, a);
        if (!strcmp(head, "add")) return hl_add(pool, a, b);
        if (!strcmp(head, "sub")) return hl_sub(pool, a, b);
        if (!strcmp(head, "mul")) return hl_mul(pool, a, b);
        if (!strcmp(head, "div")) return hl_div(pool, a, b);
        if (!strcmp(head, "pow")) return hl_pow(pool, a, b);
        int f = hl_fun_lookup(head, (int)strlen(head));
        if (f < 0) {
            fprintf(stderr, "sx: bad head %s\n", head);
            abort();
        }
        return b != NULL ? hl_call2(pool, (hl_fun)f, a, b) : hl_call(pool, (hl_fun)f, a);
    }
    char atom[256];
    int n = 0;
    while (**s && **s != ' ' && **s != ')' && n < 255)
        atom[n++] = *(*s)++;
    atom[n] = '\0';
    if (isdigit((unsigned char)atom[0]) || (atom[0] == '-' && isdigit((unsigned char)atom[1]))) {
        fmpq_t q;
        fmpq_init(q);
        if (fmpq_set_str(q, atom, 10) != 0) {
            fprintf(stderr, "sx: bad number %s\n", atom);
            abort();
        }
        fmpq_canonicalise(q);
        const hl_expr *e = hl_num_fmpq(pool, q);
        fmpq_clear(q);
        return e;
    }
    if (!strcmp(atom, "pi"))
        return hl_pi(pool);
    return hl_sym(pool, atom);
}

static inline const hl_expr *sx(hl_pool *pool, const char *s)
{
    return sx_read(pool, &s);
}

#endif
