/* The machine's measured peak for the onboard step's physical floor:
 * multiply-adds (two flops each) on independent lanes, and the exported
 * C's own exponential (exp_neg11 of an f64 export, included from its
 * dtg_model.c) over a block of arguments, on the instruction set of the
 * flags given (-O3: gcc at -O2 vectorises the step's exponential loop in
 * dtg_model.c but not this file's; -mavx2 for the kernels' AVX2 clone).
 *
 *     cc -O3 [-mavx2] -std=c99 -I C_DIR peak.c -lm -o peak
 *     ./peak      prints "GFLOPS GEXPS": flops per ns, exponentials per ns
 *
 * Best of 301 short runs of each (a peak, not a median; a run of about a
 * tenth of a millisecond fits in a time slice even on a loaded machine). */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <time.h>
#include "dtg_model.c"

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e9 + t.tv_nsec;
}

/* W independent multiply-add chains kept in registers: 24 cover the
 * latency of a multiply then an add on two 2-wide ports (the harness's
 * SSE2), 96 the same on wider vectors (-march=native); the best counts. */
#define FLOPS_PER_NS(NAME, W)                                           \
    static double NAME(double *sink) {                                  \
        enum { REPS = 4000 * 24 / W };                                  \
        double a[W], m = 0.9999999, d = 1e-9, best = 0, t0;             \
        int k, r, run;                                                  \
        for (run = 0; run < 301; run++) {                               \
            for (k = 0; k < W; k++) a[k] = 1.0 + k;                     \
            t0 = now_ns();                                              \
            for (r = 0; r < REPS; r++)                                  \
                for (k = 0; k < W; k++) a[k] = a[k] * m + d;            \
            t0 = now_ns() - t0;                                         \
            if (2.0 * W * REPS / t0 > best) best = 2.0 * W * REPS / t0; \
            for (k = 0; k < W; k++) *sink += a[k];                      \
        }                                                               \
        return best;                                                    \
    }
FLOPS_PER_NS(flops_per_ns_24, 24)
FLOPS_PER_NS(flops_per_ns_96, 96)

static double flops_per_ns(double *sink) {
    double a = flops_per_ns_24(sink), b = flops_per_ns_96(sink);
    return a > b ? a : b;
}

/* The exported exponential over 256 arguments in -40 ... 0, eight at a
 * time as the step takes them (one per lane of a centre block, in two
 * loops of half a block). */
static double exps_per_ns(double *sink) {
    enum { B = 256, REPS = 100 };
    static double x[B], y[B];
    double best = 0, t0;
    int i, b, r, run;
    for (i = 0; i < B; i++) x[i] = -40.0 * i / B;
    for (run = 0; run < 301; run++) {
        t0 = now_ns();
        for (r = 0; r < REPS; r++) {
            for (b = 0; b < B; b += 8) {
                double arg[8], phi[8];
                for (i = 0; i < 8; i++) arg[i] = x[b + i];
                for (i = 0; i < 4; i++) phi[i] = exp_neg11(arg[i]);
                for (i = 4; i < 8; i++) phi[i] = exp_neg11(arg[i]);
                for (i = 0; i < 8; i++) y[b + i] = phi[i];
            }
            x[r % B] += 1e-12 * y[(r + 1) % B];
        }
        t0 = now_ns() - t0;
        if ((double)B * REPS / t0 > best) best = (double)B * REPS / t0;
        for (i = 0; i < B; i++) *sink += y[i];
    }
    return best;
}

int main(void) {
    double sink = 0, f = flops_per_ns(&sink), e = exps_per_ns(&sink);
    printf("%.3f %.3f\n", f, e);
    fprintf(stderr, "(checksum %g)\n", sink);
    return 0;
}
