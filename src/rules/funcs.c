/* The language's functions, the tape operations that compute them and the
 * point functions the rules call: one table, read by every back end (the
 * libm name for the compilers, the double value for the interpreter, the
 * hl_fun for the exact back ends), so that a new function is one row. */
#include <math.h>

#include "rules/rule.h"

typedef struct pfn_row {
    const char *name; /* libm's */
    hl_fun fun;       /* the language's; HL_FUN_COUNT for pow */
    int arity;
} pfn_row;

static const pfn_row pfn[HL_PFN_COUNT] = {
    [HL_PFN_SIN] = {"sin", HL_SIN, 1},       [HL_PFN_COS] = {"cos", HL_COS, 1},
    [HL_PFN_TAN] = {"tan", HL_TAN, 1},       [HL_PFN_SINH] = {"sinh", HL_SINH, 1},
    [HL_PFN_COSH] = {"cosh", HL_COSH, 1},    [HL_PFN_TANH] = {"tanh", HL_TANH, 1},
    [HL_PFN_EXP] = {"exp", HL_EXP, 1},       [HL_PFN_LOG] = {"log", HL_LOG, 1},
    [HL_PFN_SQRT] = {"sqrt", HL_SQRT, 1},    [HL_PFN_ATAN] = {"atan", HL_ATAN, 1},
    [HL_PFN_ASIN] = {"asin", HL_ASIN, 1},    [HL_PFN_ACOS] = {"acos", HL_ACOS, 1},
    [HL_PFN_ASINH] = {"asinh", HL_ASINH, 1}, [HL_PFN_ATAN2] = {"atan2", HL_ATAN2, 2}, [HL_PFN_POW] = {"pow", HL_FUN_COUNT, 2},
};

/* by function: the op, and whether the value is its second result */
static const struct {
    hl_op op;
    int second;
} fun_op[HL_FUN_COUNT] = {
    [HL_SIN] = {HL_OP_SINCOS, 0},    [HL_COS] = {HL_OP_SINCOS, 1},
    [HL_SINH] = {HL_OP_SINHCOSH, 0}, [HL_COSH] = {HL_OP_SINHCOSH, 1},
    [HL_TAN] = {HL_OP_TAN, 0},       [HL_TANH] = {HL_OP_TANH, 0},
    [HL_EXP] = {HL_OP_EXP, 0},       [HL_LOG] = {HL_OP_LOG, 0},
    [HL_SQRT] = {HL_OP_SQRT, 0},     [HL_ATAN] = {HL_OP_ATAN, 0},
    [HL_ASIN] = {HL_OP_ASIN, 0},     [HL_ACOS] = {HL_OP_ACOS, 0},
    [HL_ASINH] = {HL_OP_ASINH, 0},   [HL_ATAN2] = {HL_OP_ATAN2, 0},
};

const char *hl_pfn_name(hl_pfn f) { return pfn[f].name; }
hl_fun hl_pfn_fun(hl_pfn f) { return pfn[f].fun; }
int hl_pfn_arity(hl_pfn f) { return pfn[f].arity; }

hl_op hl_fun_op(hl_fun f, int *second)
{
    if (second != NULL)
        *second = fun_op[f].second;
    return fun_op[f].op;
}

double hl_pfn_eval(hl_pfn f, double a, double b)
{
    switch (f) {
    case HL_PFN_SIN: return sin(a);
    case HL_PFN_COS: return cos(a);
    case HL_PFN_TAN: return tan(a);
    case HL_PFN_SINH: return sinh(a);
    case HL_PFN_COSH: return cosh(a);
    case HL_PFN_TANH: return tanh(a);
    case HL_PFN_EXP: return exp(a);
    case HL_PFN_LOG: return log(a);
    case HL_PFN_SQRT: return sqrt(a);
    case HL_PFN_ATAN: return atan(a);
    case HL_PFN_ASIN: return asin(a);
    case HL_PFN_ACOS: return acos(a);
    case HL_PFN_ASINH: return asinh(a);
    case HL_PFN_ATAN2: return atan2(a, b);
    case HL_PFN_POW:
    case HL_PFN_COUNT: break;
    }
    return pow(a, b);
}
