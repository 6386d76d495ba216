/* The tape and flow tests' systems: the tape of H in (x, px) or (x, y, px,
 * py), on the test's pool; a formula that does not parse fails the test. */
#ifndef HAMLIE_TAPE_TEST_HAMILTONIAN_H
#define HAMLIE_TAPE_TEST_HAMILTONIAN_H

#include "hl_test.h"
#include "hamlie/tape.h"

static hl_tape *test_hamiltonian(hl_pool *P, const char *H, int N)
{
    static const char *const q[] = {"x", "y"}, *const p[] = {"px", "py"};
    const hl_expr *h;
    hl_error err;
    CHECK_MSG(hl_parse(&h, P, H, &err) == HL_OK, "%s", H);
    hl_tape *t = NULL;
    CHECK_MSG(hl_tape_hamiltonian(&t, P, h, N, q, p, 0, NULL, NULL, &err) == HL_OK, "%s", err.msg);
    return t;
}

#endif
