/* Small assertion helpers for the Lignum tests: every CHECK prints what it
 * checks, and the test exits with the number of failures. */
#ifndef LGN_TEST_UTIL_H
#define LGN_TEST_UTIL_H

#include <math.h>
#include <stdio.h>

static int test_failures = 0;
static int test_checks   = 0;

#define CHECK(cond, ...)                                                \
  do {                                                                  \
    test_checks++;                                                      \
    if (!(cond)) {                                                      \
      test_failures++;                                                  \
      printf("FAIL %s:%d: ", __FILE__, __LINE__);                       \
      printf(__VA_ARGS__);                                              \
      printf("\n");                                                     \
    }                                                                   \
  } while (0)

/* |actual - expected| <= tol, reported with both values. */
#define CHECK_CLOSE(actual, expected, tol, what)                        \
  do {                                                                  \
    double a_ = (actual), e_ = (expected), t_ = (tol);                  \
    test_checks++;                                                      \
    if (!(fabs(a_ - e_) <= t_)) {                                       \
      test_failures++;                                                  \
      printf("FAIL %s:%d: %s = %.12g, expected %.12g (tol %.3g)\n",     \
             __FILE__, __LINE__, what, a_, e_, t_);                     \
    }                                                                   \
  } while (0)

static int test_summary(const char *name)
{
  printf("%s: %d checks, %d failures\n", name, test_checks, test_failures);
  return test_failures == 0 ? 0 : 1;
}

#endif
