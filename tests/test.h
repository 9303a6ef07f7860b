/* test.h: the tiny assertion kit every ctest uses. A failed CHECK prints the
 * file, line and expression and makes the test exit 1; TEST_SKIP exits 77. */
#ifndef MEADOW_TEST_H
#define MEADOW_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int test_failures;

#define CHECK(cond)                                                             \
    do {                                                                        \
        if (!(cond)) {                                                          \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            test_failures++;                                                    \
        }                                                                       \
    } while (0)

#define CHECK_MSG(cond, ...)                                                    \
    do {                                                                        \
        if (!(cond)) {                                                          \
            fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                       \
            fputc('\n', stderr);                                                \
            test_failures++;                                                    \
        }                                                                       \
    } while (0)

#define CHECK_NEAR(a, b, eps)                                                   \
    do {                                                                        \
        double a_ = (double)(a), b_ = (double)(b);                              \
        if (!(fabs(a_ - b_) <= (eps))) {                                        \
            fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s=%g %s=%g eps=%g\n",   \
                    __FILE__, __LINE__, #a, a_, #b, b_, (double)(eps));         \
            test_failures++;                                                    \
        }                                                                       \
    } while (0)

/* Euclidean distance of two float[3] points, in double. */
static inline double test_dist3(const float *a, const float *b)
{
    double s = 0;
    for (int k = 0; k < 3; k++) s += ((double)a[k] - b[k]) * ((double)a[k] - b[k]);
    return sqrt(s);
}

#define TEST_SKIP(...)                                                          \
    do {                                                                        \
        fprintf(stderr, "SKIP: " __VA_ARGS__);                                  \
        fputc('\n', stderr);                                                    \
        exit(77);                                                               \
    } while (0)

#define TEST_END()                                                              \
    do {                                                                        \
        if (test_failures) {                                                    \
            fprintf(stderr, "%d check(s) failed\n", test_failures);             \
            return 1;                                                           \
        }                                                                       \
        printf("ok\n");                                                         \
        return 0;                                                               \
    } while (0)

#endif
