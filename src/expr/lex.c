/* Tokenizer: numbers are read as exact rationals (0.1 is 1/10), every token
 * carries its byte span so errors can point at it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "expr/lex.h"

static int is_digit(int c) { return c >= '0' && c <= '9'; }
static int is_letter(int c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
static int is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

void hl_lex_init(hl_lexer *lx, const char *src, int values)
{
    lx->src = src;
    lx->pos = 0;
    lx->values = values;
    lx->tok.kind = HL_TK_EOF;
    lx->tok.pos = 0;
    lx->tok.len = 0;
    fmpq_init(lx->num);
}

void hl_lex_clear(hl_lexer *lx)
{
    fmpq_clear(lx->num);
}

void hl_lex_text(char *out, size_t size, const char *src, hl_token t)
{
    if (t.kind == HL_TK_EOF) {
        snprintf(out, size, "end of formula");
        return;
    }
    int n = t.len > 32 ? 32 : t.len;
    snprintf(out, size, "%.*s%s", n, src + t.pos, t.len > n ? "..." : "");
}

/* digits [. digits] [(e|E) [+|-] digits] starting at lx->pos; the value is
 * mantissa * 10^(exponent - fraction digits), built exactly. */
/* x *= 10^e, exactly.  gcc 12 misreads FLINT's inline fmpq functions
 * (-Wstringop-overflow on a 16-byte fmpq "in a region of size 8"): a false
 * positive, silenced for this function only. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#pragma GCC diagnostic ignored "-Wstringop-overread"
static void scale_by_power_of_ten(fmpq_t x, long e)
{
    fmpz_t n, d, t;
    fmpz_init_set(n, fmpq_numref(x));
    fmpz_init_set(d, fmpq_denref(x));
    fmpz_init_set_ui(t, 10);
    fmpz_pow_ui(t, t, (ulong)(e > 0 ? e : -e));
    if (e > 0)
        fmpz_mul(n, n, t);
    else
        fmpz_mul(d, d, t);
    fmpq_set_fmpz_frac(x, n, d);
    fmpz_clear(n);
    fmpz_clear(d);
    fmpz_clear(t);
}
#pragma GCC diagnostic pop

static int lex_number(hl_lexer *lx, hl_error *err)
{
    const char *s = lx->src;
    int p = lx->pos, start = p, frac = 0;

    while (is_digit(s[p]))
        p++;
    int int_end = p;
    if (s[p] == '.') {
        p++;
        if (!is_digit(s[p])) {
            lx->pos = p;
            lx->tok.kind = HL_TK_NUM;
            lx->tok.pos = start;
            lx->tok.len = p - start;
            return hl_error_set(err, HL_EPARSE, lx->src, p, 1, "expected a digit after '.'");
        }
        while (is_digit(s[p]))
            p++, frac++;
    }
    int mant_end = p;
    long exp10 = 0;
    int exp_pos = -1;
    if ((s[p] == 'e' || s[p] == 'E') &&
        (is_digit(s[p + 1]) || ((s[p + 1] == '+' || s[p + 1] == '-') && is_digit(s[p + 2])))) {
        exp_pos = p;
        int neg = s[p + 1] == '-';
        p += (s[p + 1] == '+' || s[p + 1] == '-') ? 2 : 1;
        while (is_digit(s[p])) {
            if (exp10 <= HL_EXP10_MAX) /* saturate: only "too large" matters */
                exp10 = 10 * exp10 + (s[p] - '0');
            p++;
        }
        if (neg)
            exp10 = -exp10;
    }
    lx->pos = p;
    lx->tok.kind = HL_TK_NUM;
    lx->tok.pos = start;
    lx->tok.len = p - start;
    if (exp10 > HL_EXP10_MAX || exp10 < -HL_EXP10_MAX)
        return hl_error_set(err, HL_ELIMIT, lx->src, exp_pos, p - exp_pos,
                            "exponent too large (the limit is 1e%d)", HL_EXP10_MAX);
    if (!lx->values)
        return HL_OK;

    /* the mantissa's digits without the point */
    char *digits = hl_xmalloc((size_t)(mant_end - start) + 1);
    int nd = 0;
    for (int i = start; i < mant_end; i++)
        if (i != int_end)
            digits[nd++] = s[i];
    digits[nd] = '\0';
    fmpz_set_str(fmpq_numref(lx->num), digits, 10);
    free(digits);
    fmpz_one(fmpq_denref(lx->num));

    long e = exp10 - frac;
    if (!fmpz_is_zero(fmpq_numref(lx->num)) && e != 0)
        scale_by_power_of_ten(lx->num, e);
    return HL_OK;
}

int hl_lex_next(hl_lexer *lx, hl_error *err)
{
    const char *s = lx->src;
    int p = lx->pos;

    while (is_space((unsigned char)s[p]))
        p++;
    lx->pos = p;
    lx->tok.pos = p;
    lx->tok.len = 1;
    int c = (unsigned char)s[p];
    if (c == '\0') {
        lx->tok.kind = HL_TK_EOF;
        lx->tok.len = 0;
        return HL_OK;
    }
    if (is_digit(c))
        return lex_number(lx, err);
    if (is_letter(c)) {
        while (is_letter((unsigned char)s[p]) || is_digit(s[p]) || s[p] == '_')
            p++;
        lx->tok.kind = HL_TK_NAME;
        lx->tok.len = p - lx->pos;
        lx->pos = p;
        return HL_OK;
    }
    lx->pos = p + 1;
    switch (c) {
    case '+': lx->tok.kind = HL_TK_PLUS; return HL_OK;
    case '-': lx->tok.kind = HL_TK_MINUS; return HL_OK;
    case '/': lx->tok.kind = HL_TK_SLASH; return HL_OK;
    case '^': lx->tok.kind = HL_TK_POW; return HL_OK;
    case '(': lx->tok.kind = HL_TK_LPAREN; return HL_OK;
    case ')': lx->tok.kind = HL_TK_RPAREN; return HL_OK;
    case '=': lx->tok.kind = HL_TK_EQ; return HL_OK;
    case ';': lx->tok.kind = HL_TK_SEMI; return HL_OK;
    case ',': lx->tok.kind = HL_TK_COMMA; return HL_OK;
    case '*':
        if (s[p + 1] == '*') { /* ** is ^ */
            lx->tok.kind = HL_TK_POW;
            lx->tok.len = 2;
            lx->pos = p + 2;
        } else {
            lx->tok.kind = HL_TK_STAR;
        }
        return HL_OK;
    }
    lx->tok.kind = HL_TK_EOF;
    if (c == '.')
        return hl_error_set(err, HL_EPARSE, lx->src, p, 1,
                            "unexpected character '.' (a number starts with a digit: 0.5)");
    if (c >= 0x20 && c < 0x7f)
        return hl_error_set(err, HL_EPARSE, lx->src, p, 1, "unexpected character '%c'", c);
    return hl_error_set(err, HL_EPARSE, lx->src, p, 1, "unexpected byte 0x%02x", c);
}
