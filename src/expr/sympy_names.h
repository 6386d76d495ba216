/* Names sympify would not read as a plain symbol: Python keywords and
 * sympy's own names a physicist may well use (the SYMPY printer writes them
 * Symbol('E')).  Kept in strcmp (byte) order: the printer looks a name up by
 * binary search, and t-print checks every entry is found.  Included by
 * print.c and its test only. */
#ifndef HAMLIE_EXPR_SYMPY_NAMES_H
#define HAMLIE_EXPR_SYMPY_NAMES_H

/* clang-format off */
static const char *const hl_sympy_reserved[] = {
    "Abs", "Add", "And", "CC", "Chi", "Ci", "Circle", "Curve", "Derivative", "Dict",
    "DiracDelta", "Dummy", "E", "EX", "Ei", "Eijk", "EmptySet", "Eq", "FF", "False",
    "FiniteSet", "Float", "Function", "GF", "Ge", "Gt", "Heaviside", "I", "Id", "Integer",
    "Integral", "Interval", "KroneckerDelta", "Lambda", "Le", "LeviCivita", "Li", "Line", "Lt",
    "Matrix", "Max", "Min", "Mod", "Mul", "N", "Ne", "None", "Not", "Number", "O", "Or",
    "Order", "Piecewise", "Plane", "Point", "Poly", "Polygon", "Pow", "Product", "Q", "QQ",
    "QQ_I", "RR", "Range", "Rational", "Ray", "S", "Segment", "Set", "Shi", "Si", "Sum",
    "Symbol", "Triangle", "True", "Tuple", "Union", "Wild", "Xor", "Ynm", "ZZ", "ZZ_I", "Znm",
    "acos", "acosh", "acot", "acoth", "acsc", "adjoint", "and", "apart", "arg", "as", "asec",
    "asin", "asinh", "ask", "assert", "async", "atan", "atan2", "atanh", "await", "bell",
    "bernoulli", "besseli", "besselj", "besselk", "bessely", "beta", "break", "cancel",
    "catalan", "cbrt", "ceiling", "chebyshevt", "chebyshevu", "class", "conjugate", "content",
    "continue", "cos", "cosh", "cot", "coth", "csc", "csch", "cse", "def", "deg", "degree",
    "del", "denom", "det", "diff", "digamma", "div", "divisors", "elif", "else", "erf", "erfc",
    "euler", "evaluate", "except", "exp", "exp_polar", "expand", "eye", "factor", "false",
    "ff", "fibonacci", "field", "finally", "floor", "for", "frac", "from", "gamma", "gcd",
    "global", "harmonic", "hermite", "hyper", "if", "im", "import", "in", "integrate", "is",
    "jn", "laguerre", "lambda", "lambdify", "latex", "lcm", "legendre", "li", "limit", "ln",
    "log", "loggamma", "lowergamma", "lucas", "mod", "nan", "nonlocal", "not", "nsimplify",
    "numer", "ones", "oo", "or", "pass", "pi", "plot", "poly", "polygamma", "prime", "quo",
    "rad", "raise", "re", "real_root", "refine", "rem", "residue", "return", "rf", "ring",
    "root", "roots", "sec", "sech", "series", "sign", "simplify", "sin", "sinc", "sinh",
    "solve", "sqrt", "srepr", "symbols", "sympify", "tan", "tanh", "test", "together",
    "totient", "trace", "transpose", "true", "try", "uppergamma", "var", "while", "with",
    "yield", "yn", "zeros", "zeta", "zoo",
};
/* clang-format on */

#endif
