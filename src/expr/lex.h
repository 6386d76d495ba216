/* The tokenizer of the expression language (internal to src/expr). */
#ifndef HAMLIE_EXPR_LEX_H
#define HAMLIE_EXPR_LEX_H

#include <flint/fmpq.h>
#include "hamlie/error.h"

typedef enum hl_tok_kind {
    HL_TK_EOF,    /* end of the formula */
    HL_TK_NUM,    /* 12, 0.25, 1e-3: value in lexer num */
    HL_TK_NAME,   /* letter {letter | digit | _} */
    HL_TK_PLUS,   /* + */
    HL_TK_MINUS,  /* - */
    HL_TK_STAR,   /* * */
    HL_TK_SLASH,  /* / */
    HL_TK_POW,    /* ^ or ** */
    HL_TK_LPAREN, /* ( */
    HL_TK_RPAREN, /* ) */
    HL_TK_EQ,     /* = */
    HL_TK_SEMI,   /* ; */
    HL_TK_COMMA   /* , between the arguments of atan2 */
} hl_tok_kind;

typedef struct hl_token {
    hl_tok_kind kind;
    int pos, len; /* byte span in the source */
} hl_token;

#define HL_EXP10_MAX 10000 /* |e| allowed in 1e<e> */

typedef struct hl_lexer {
    const char *src;
    int pos;         /* next byte to read */
    int values;      /* compute number values (off for hl_symbol_pos) */
    hl_token tok;    /* the current token */
    fmpq_t num;      /* value of the current HL_TK_NUM */
} hl_lexer;

void hl_lex_init(hl_lexer *lx, const char *src, int values);
void hl_lex_clear(hl_lexer *lx);

/* Read the next token into lx->tok.  On a bad character or number, returns
 * the status with err filled; the lexer has moved past the bad spot. */
int hl_lex_next(hl_lexer *lx, hl_error *err);

/* Quote a token's text for a message: at most 32 bytes, then "...". */
void hl_lex_text(char *out, size_t size, const char *src, hl_token t);

#endif
