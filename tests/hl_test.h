/* Minimal test harness: CHECK records a failure with file:line and goes on;
 * HL_TEST_END prints "N passed, N failed" and returns non-zero on failure. */
#ifndef HL_TEST_H
#define HL_TEST_H

#include <stdio.h>
#include <string.h>

static int hl_test_passed, hl_test_failed;

#define CHECK(cond)                                                            \
    do {                                                                       \
        if (cond)                                                              \
            hl_test_passed++;                                                  \
        else {                                                                 \
            hl_test_failed++;                                                  \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__,   \
                    #cond);                                                    \
        }                                                                      \
    } while (0)

#define CHECK_MSG(cond, ...)                                                   \
    do {                                                                       \
        if (cond)                                                              \
            hl_test_passed++;                                                  \
        else {                                                                 \
            hl_test_failed++;                                                  \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__,   \
                    #cond);                                                    \
            fprintf(stderr, __VA_ARGS__);                                      \
            fputc('\n', stderr);                                               \
        }                                                                      \
    } while (0)

#define CHECK_STR(got, want)                                                   \
    CHECK_MSG(strcmp((got), (want)) == 0, "got \"%s\", want \"%s\"", (got), (want))

#define HL_TEST_END()                                                          \
    (printf("%d passed, %d failed\n", hl_test_passed, hl_test_failed),         \
     hl_test_failed != 0)

#endif
